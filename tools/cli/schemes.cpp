// Scheme names on the command line (docs/design.md §6).
#include <cstdio>

#include "commands.hpp"
#include "curvenet/error.hpp"

namespace curvenet::cli {

Scheme parseScheme(const std::string &name) {
  if (auto scheme = schemeFromName(name)) return *scheme;
  std::string known;
  for (Scheme s : availableSchemes()) known += (known.empty() ? "" : ", ") + schemeName(s);
  throw InputError("", "--scheme", "unknown or not yet available scheme '" + name + "'; available: " + known);
}

void addMastersOption(CLI::App *sub, std::string &masters) {
  sub->add_option("--masters", masters,
                  "gregory-g2 over the faces edges name as masters: rebuilt (G2 patches) | kept-g1 (their G1 patches, "
                  "which the G2 faces meet curvature continuously)")
      ->capture_default_str();
}

SurfaceOptions parseSurfaceOptions(const std::string &scheme, const std::string &masters) {
  SurfaceOptions options;
  options.scheme = parseScheme(scheme);
  const std::optional<MasterFaces> m = masterFacesFromName(masters);
  if (!m)
    throw InputError("", "--masters", "unknown value '" + masters + "'; available: " +
                                          masterFacesName(MasterFaces::Rebuilt) + ", " +
                                          masterFacesName(MasterFaces::KeptG1));
  if (*m != MasterFaces::Rebuilt && options.scheme != Scheme::GregoryG2)
    throw InputError("", "--masters", masters + " needs --scheme gregory-g2 (other schemes build every face alike)");
  options.masterFaces = *m;
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
