// Scheme names on the command line (docs/design.md §6).
#include <algorithm>
#include <cstdio>

#include "commands.hpp"
#include "curvenet/error.hpp"

namespace curvenet::cli {

Scheme parseScheme(const std::string &name) {
  if (auto scheme = schemeFromName(name)) return *scheme;
  std::string known;
  for (Scheme s : availableSchemes()) known += (known.empty() ? "" : ", ") + schemeName(s);
  throw UsageError("--scheme", "unknown or not yet available scheme '" + name + "'; available: " + known);
}

void addMastersOption(CLI::App *sub, std::string &masters) {
  sub->add_option("--masters", masters,
                  "gregory-g2 over the faces edges name as masters: rebuilt (G2 patches) | kept-g1 (their G1 patches, "
                  "which the G2 faces meet curvature continuously)")
      ->capture_default_str();
}

void addCurvesOption(CLI::App *sub, std::string &curves) {
  sub->add_option("--curves", curves,
                  "repaired (turn end tangents into the vertex tangent plane where they leave it; gregory-g2 also "
                  "tweaks curvatures to the fitted vertex tensor) | kept (the curves as given)")
      ->capture_default_str();
}

void addStrictFlag(CLI::App *sub, bool &strict) {
  sub->add_flag("--strict", strict,
                "fail (exit 1, writing nothing) when a face folds, passes through a face or its excursion exceeds " +
                    std::to_string(int(kExcursionBound * 100)) + "% of the diagonal");
}

SurfaceOptions parseSurfaceOptions(const std::string &scheme, const std::string &masters, const std::string &curves) {
  SurfaceOptions options;
  options.scheme = parseScheme(scheme);
  const std::optional<MasterFaces> m = masterFacesFromName(masters);
  if (!m)
    throw UsageError("--masters", "unknown value '" + masters + "'; available: " +
                                          masterFacesName(MasterFaces::Rebuilt) + ", " +
                                          masterFacesName(MasterFaces::KeptG1));
  if (*m != MasterFaces::Rebuilt && options.scheme != Scheme::GregoryG2)
    throw UsageError("--masters", masters + " needs --scheme gregory-g2 (other schemes build every face alike)");
  options.masterFaces = *m;
  const std::optional<CurveHandling> c = curveHandlingFromName(curves);
  if (!c)
    throw UsageError("--curves", "unknown value '" + curves + "'; available: repaired, kept");
  options.curves = *c;
  return options;
}

void warnAboutFolds(const Surface &surface) {
  for (int face : surface.foldedFaces())
    std::fprintf(stderr,
                 "curvenet: warning: face %d: the %s patch folds over itself (its normal turns over inside the face); "
                 "split the face with an extra curve or try another scheme\n",
                 face, schemeName(surface.faceOptions(face).scheme).c_str());
}

} // namespace curvenet::cli

namespace curvenet::cli {

void enforceShape(const Surface &surface, const ShapeReport &shape, bool strict) {
  std::string rejected;
  for (int f : shape.rejectedFaces) {
    const FaceShape &face = shape.faces[size_t(f)];
    rejected += (rejected.empty() ? "" : ", ") + std::to_string(f);
    if (!strict && !face.folded && !(face.excursion <= kExcursionBound))
      std::fprintf(stderr,
                   "curvenet: warning: face %d: the %s patch leaves its boundary's box by %.3g of the diagonal "
                   "(bound %.3g)\n",
                   f, schemeName(surface.faceOptions(f).scheme).c_str(), face.excursion, kExcursionBound);
  }
  if (!strict)
    for (const CornerFold &c : shape.cornerFolds)
      std::fprintf(stderr,
                   "curvenet: warning: face %d: the %s patch folds near its corner %d (its normal turns over within "
                   "%.2g of the diagonal of the corner, closer than the fold check's grid; typically where the "
                   "corner's two curves leave it in nearly the same direction): try another scheme or bend the "
                   "curves apart\n",
                   c.face, schemeName(surface.faceOptions(c.face).scheme).c_str(), c.corner, c.extent);
  if (!strict)
    for (const FaceIntersection &x : shape.intersections) {
      const std::string where = x.faceA == x.faceB ? "face " + std::to_string(x.faceA) + ": the " +
                                                         schemeName(surface.faceOptions(x.faceA).scheme) +
                                                         " patch passes through itself"
                                                   : "faces " + std::to_string(x.faceA) + " and " +
                                                         std::to_string(x.faceB) + ": the " +
                                                         schemeName(surface.faceOptions(x.faceA).scheme) +
                                                         " patches pass through each other";
      std::fprintf(stderr,
                   "curvenet: warning: %s near (%.4g, %.4g, %.4g), where no normal turns over in either's own "
                   "parameters (typically a patch curling over a thin part of the model): try another scheme\n",
                   where.c_str(), x.point.x, x.point.y, x.point.z);
    }
  if (strict && !rejected.empty())
    throw InputError("", "faces " + rejected,
                     "the surface folds, passes through itself or leaves its boundary's box by more than " +
                         std::to_string(kExcursionBound) + " of the diagonal (largest excursion " +
                         std::to_string(shape.maxExcursion) + ", " + std::to_string(shape.foldedFaces.size()) +
                         " folded faces, " + std::to_string(shape.cornerFolds.size()) + " corner folds, " +
                         std::to_string(shape.intersections.size()) + " face intersections); --strict writes nothing");
}

void noteRepair(const Surface &surface) {
  const std::vector<RepairMove> &moves = surface.repairMoves();
  if (moves.empty()) return;
  std::vector<int> vertices;
  double largest = 0;
  for (const RepairMove &m : moves) {
    if (std::find(vertices.begin(), vertices.end(), m.vertex) == vertices.end()) vertices.push_back(m.vertex);
    largest = std::max(largest, m.sizeRelative);
  }
  std::fprintf(stderr,
               "curvenet: repaired the curves at %zu vertices (%zu control points moved, largest move %.3g of the "
               "diagonal; --curves kept builds on the curves as given)\n",
               vertices.size(), moves.size(), largest);
}

} // namespace curvenet::cli
