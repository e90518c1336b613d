#include "report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <numbers>

#include "curvenet/continuity.hpp"
#include "curvenet/curvature_jump.hpp"
#include "curvenet/master_contact.hpp"
#include "curvenet/shape.hpp"

namespace curvenet::cli {

nlohmann::json networkReport(const Network &network, const std::string &input) {
  using nlohmann::json;
  json report;
  report["input"] = input;
  report["name"] = network.name();
  report["diagonal"] = network.diagonal();
  report["patches"] = network.faces().size();
  report["segments"] = network.segments().size();
  std::map<std::string, int> bySides;
  for (const Face &face : network.faces()) ++bySides[std::to_string(face.sideCount())];
  report["faces_by_sides"] = bySides;
  json vertices = json::array();
  for (size_t v = 0; v < network.vertices().size(); ++v) {
    const Vertex &vertex = network.vertices()[v];
    vertices.push_back({{"index", v},
                        {"position", {vertex.position.x, vertex.position.y, vertex.position.z}},
                        {"kind", toString(vertex.kind)},
                        {"valence", vertex.valence},
                        {"independent_curves", vertex.independentCurves},
                        {"boundary", vertex.onBoundary}});
  }
  report["vertices"] = std::move(vertices);
  return report;
}

namespace {

/// Faces split by connection curves ([SV14] Sec. 5.2) are the user's one
/// face: each composite lists its patches, its hidden seams (the connection
/// segments) and the curvature jump across them.
void addCompositeFaces(nlohmann::json &report, const Surface &surface, const CurvatureJumpReport &jump) {
  const Network &network = surface.network();
  std::map<int, nlohmann::json> composites;
  for (size_t f = 0; f < network.faces().size(); ++f) {
    const int user = network.faces()[f].partOf;
    nlohmann::json &c = composites[user];
    c["face"] = user;
    c["patches"].push_back(f);
    if (std::find(surface.foldedFaces().begin(), surface.foldedFaces().end(), static_cast<int>(f)) !=
        surface.foldedFaces().end())
      c["folded"] = true;
  }
  bool anySplit = false;
  for (size_t e = 0; e < network.segments().size(); ++e) {
    const Segment &seg = network.segments()[e];
    if (!seg.connection || seg.faces[0] < 0) continue;
    anySplit = true;
    nlohmann::json &c = composites[network.faces()[seg.faces[0]].partOf];
    c["hidden_seams"].push_back(e);
    double worst = c.value("max_seam_curvature_jump", 0.0);
    for (const CurvatureJumpSample &sample : jump.samples)
      if (sample.segment == static_cast<int>(e)) worst = std::max(worst, sample.jump);
    c["max_seam_curvature_jump"] = worst;
  }
  if (!anySplit) return;
  nlohmann::json list = nlohmann::json::array();
  for (auto &[user, c] : composites)
    if (c["patches"].size() > 1) {
      c["folded"] = c.value("folded", false);
      list.push_back(c);
    }
  report["faces"] = composites.size();
  report["composite_faces"] = list;
}

} // namespace

nlohmann::json repairReport(const Surface &surface) {
  nlohmann::json moves = nlohmann::json::array();
  double largest = 0;
  for (const RepairMove &m : surface.repairMoves()) {
    moves.push_back({{"vertex", m.vertex},
                     {"curve", m.curve},
                     {"kind", toString(m.kind)},
                     {"size", m.size},
                     {"size_relative", m.sizeRelative},
                     {"angle_deg", m.angle * 180 / std::numbers::pi}});
    largest = std::max(largest, m.sizeRelative);
  }
  return {{"curves", curveHandlingName(surface.options().curves)},
          {"moves", std::move(moves)},
          {"max_move_relative", largest},
          {"skipped", surface.repairSkipped()},
          {"note", "control points moved by the vertex repair (tangent-plane: end tangent turned into the vertex "
                   "plane; curvature: normal curvature set to the fitted tensor); sizes relative to the diagonal; "
                   "vertices never move; skipped: what the repair left alone, with the reason"}};
}

/// The crease vertices and segments (Surface::isCreaseVertex,
/// isCreaseSegment) and the segments the surface is G1 across.
void addCreases(nlohmann::json &report, const Surface &surface) {
  const Network &network = surface.network();
  std::vector<int> vertices, creases, smooth;
  for (int v = 0; v < static_cast<int>(network.vertices().size()); ++v)
    if (surface.isCreaseVertex(v)) vertices.push_back(v);
  for (int e = 0; e < static_cast<int>(network.segments().size()); ++e) {
    if (network.segments()[e].isBoundary()) continue;
    (surface.isCreaseSegment(e) ? creases : smooth).push_back(e);
  }
  report["creases"] = {{"vertices", vertices}, {"segments", creases}, {"g1_segments", smooth}};
}

nlohmann::json shapeReport(const ShapeReport &shape) {
  nlohmann::json faces = nlohmann::json::array();
  for (const FaceShape &f : shape.faces)
    faces.push_back({{"face", f.face}, {"folded", f.folded}, {"folds_at_corner", f.foldsAtCorner},
                     {"intersects", f.intersects}, {"excursion", f.excursion}, {"fairness", f.fairness}});
  nlohmann::json corners = nlohmann::json::array();
  for (const CornerFold &c : shape.cornerFolds) corners.push_back({{"face", c.face}, {"corner", c.corner}, {"extent", c.extent}});
  nlohmann::json intersections = nlohmann::json::array();
  for (const FaceIntersection &x : shape.intersections)
    intersections.push_back({{"faces", {x.faceA, x.faceB}}, {"point", {x.point.x, x.point.y, x.point.z}}});
  return {{"folded_faces", shape.foldedFaces},
          {"corner_folds", std::move(corners)},
          {"intersections", std::move(intersections)},
          {"max_excursion", shape.maxExcursion},
          {"worst_excursion_face", shape.worstExcursionFace},
          {"excursion_bound", kExcursionBound},
          {"fairness", shape.fairness},
          {"max_fairness", shape.maxFairness},
          {"worst_fairness_face", shape.worstFairnessFace},
          {"rejected_faces", shape.rejectedFaces},
          {"acceptable", shape.acceptable()},
          {"faces", std::move(faces)},
          {"definitions", "excursion: growth of the bounding-box diagonal of the face's boundary curves when its "
                          "patch samples are added, relative to the model diagonal; fairness: area mean of "
                          "k1^2 + k2^2 over the face divided by the arc-length mean of k^2 along its boundary "
                          "(2 for a sphere-cap face); corner fold: the normal turning over within 0.2 of a "
                          "corner's neighbourhood in the domain, extent relative to the model diagonal; "
                          "rejected: folded (inside or at a corner) or excursion above the bound"}};
}

void addSurfaceReport(nlohmann::json &report, const Surface &surface, int samplesPerSegment, int resolution) {
  addSurfaceReport(report, surface, measureShape(surface), samplesPerSegment, resolution);
}

void addSurfaceReport(nlohmann::json &report, const Surface &surface, const ShapeReport &shape,
                      int samplesPerSegment, int resolution) {
  report["scheme"] = schemeName(surface.options().scheme);
  report["repair"] = repairReport(surface);
  report["shape"] = shapeReport(shape);
  if (surface.options().scheme == Scheme::GregoryG2) {
    report["master_faces"] = masterFacesName(surface.options().masterFaces);
    std::vector<int> kept;
    for (int f = 0; f < surface.faceCount(); ++f)
      if (surface.faceOptions(f).scheme != surface.options().scheme) kept.push_back(f);
    report["kept_g1_faces"] = kept;
  }
  report["folded_faces"] = surface.foldedFaces();
  const ContinuityReport c = measureContinuity(surface, {samplesPerSegment});
  report["continuity"] = {{"max_position_gap", c.maxPositionGap},
                          {"max_normal_angle_deg", c.maxNormalAngleDeg},
                          {"mean_normal_angle_deg", c.meanNormalAngleDeg},
                          {"max_boundary_deviation", c.maxBoundaryDeviation},
                          {"worst_normal_segment", c.worstNormalSegment},
                          {"shared_segments", c.sharedSegments},
                          {"crease_segments", c.creaseSegments},
                          {"samples", c.samples},
                          {"sampling", "every shared segment at u = j/" + std::to_string(samplesPerSegment) +
                                           ", j = 0.." + std::to_string(samplesPerSegment) +
                                           ", from both faces; normal angles on the G1 segments only (crease "
                                           "segments are sharp by design); lengths relative to the diagonal"}};
  addCreases(report, surface);
  const CurvatureJumpReport jump = measureCurvatureJump(surface);
  report["continuity"]["max_curvature_jump"] = jump.maxJump;
  report["continuity"]["mean_curvature_jump"] = jump.meanJump;
  report["continuity"]["curvature_jump_method"] =
      std::string(surface.options().scheme != Scheme::GregoryG2 ? "fourth-order differences of the exact first derivatives, step 1e-5"
                  : report["kept_g1_faces"].empty()
                      ? "exact second derivatives (hyper-dual numbers)"
                      : "exact second derivatives (hyper-dual numbers); on the kept G1 faces fourth-order differences "
                        "of the exact first derivatives, step 1e-5") +
      "; 17 points per shared segment, 1% left out at each end; |k_A - k_B| / max(|k_A|, |k_B|, 1/diagonal)";
  addCompositeFaces(report, surface, jump);
  // Master edges ([SV14] Sec. 5.1): the jump from each slave to its master.
  const std::vector<MasterEdgeJump> masters = masterEdgeJumps(surface, jump);
  if (!masters.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const MasterEdgeJump &m : masters) {
      const std::string &masterName = surface.network().faces()[size_t(m.masterFace)].name;
      list.push_back({{"edge", m.segment},
                      {"curve", m.curve},
                      {"master_face", m.masterFace},
                      {"master_name", masterName},
                      {"slave_face", m.slaveFace},
                      {"max_curvature_jump", m.maxJump},
                      {"mean_curvature_jump", m.meanJump},
                      {"samples", m.samples}});
    }
    report["masters"] = std::move(list);
  }
  // Master surfaces given from outside: each face against the surface itself.
  if (const std::vector<MasterSurfaceContact> contacts = measureMasterSurfaceContact(surface); !contacts.empty()) {
    nlohmann::json list = nlohmann::json::array();
    for (const MasterSurfaceContact &m : contacts)
      list.push_back({{"edge", m.segment},
                      {"curve", m.curve},
                      {"master_surface", m.masterSurface},
                      {"face", m.face},
                      {"max_distance", m.maxDistance},
                      {"max_normal_angle_deg", m.maxNormalAngleDeg},
                      {"max_curvature_jump", m.maxCurvatureJump},
                      {"mean_curvature_jump", m.meanCurvatureJump},
                      {"samples", m.samples}});
    report["master_surfaces"] = std::move(list);
  }
  if (const auto d = measureReferenceDeviation(surface, resolution)) {
    report["reference"] = {{"max_deviation", d->maxDeviation},
                           {"mean_deviation", d->meanDeviation},
                           {"min_signed_deviation", d->minSigned},
                           {"max_signed_deviation", d->maxSigned},
                           {"samples", d->samples},
                           {"sampling", "all vertices of the tessellation at resolution " +
                                            std::to_string(d->resolution) + "; relative to the diagonal"}};
  }
}

void addVertexAnalysis(nlohmann::json &report, const NetworkAnalysis &analysis) {
  using nlohmann::json;
  constexpr double degrees = 180 / std::numbers::pi;
  json &vertices = report["vertices"];
  for (const VertexAnalysis &va : analysis.vertices) {
    json &v = vertices.at(size_t(va.vertex));
    json psi = json::array(), kappa = json::array();
    for (double p : va.psi) psi.push_back(p * degrees);
    for (const CurveEnd &end : va.ends) kappa.push_back(end.normalCurvature);
    v["valence"] = va.valence;
    v["independent_curves"] = va.independentCurves;
    v["normal"] = {va.normal.x, va.normal.y, va.normal.z};
    v["tangent_residual_deg"] = va.tangentResidual * degrees;
    v["psi_deg"] = std::move(psi);
    v["normal_curvatures"] = std::move(kappa);
    v["curvature_scale"] = va.curvatureScale;
    v["enclosure_applies"] = va.enclosureApplies;
    v["enclosure_residual"] = va.enclosureResidualRelative;
    v["euler_residual"] = va.eulerResidualRelative;
    v["forms_x"] = va.formsX;
    v["k1"] = va.fit.tensor.k1;
    v["k2"] = va.fit.tensor.k2;
    v["lambda"] = va.fit.tensor.lambda;
    v["principal_direction1"] = {va.principalDirection1.x, va.principalDirection1.y, va.principalDirection1.z};
    v["verdict"] = toString(va.verdict);
  }
  json counts;
  for (int k = 0; k < 4; ++k) counts[toString(VertexVerdict(k))] = analysis.verdictCounts[size_t(k)];
  json worst = json::array();
  for (int v : analysis.worstFirst()) worst.push_back(v);
  report["analysis"] = {{"verdict", toString(analysis.verdict)},
                        {"vertex_verdicts", counts},
                        {"max_euler_residual", analysis.maxEulerResidualRelative},
                        {"max_enclosure_residual", analysis.maxEnclosureResidualRelative},
                        {"max_tangent_residual_deg", analysis.maxTangentResidual * degrees},
                        {"curvature_tolerance", analysis.options.curvatureTolerance},
                        {"tangent_tolerance_deg", analysis.options.tangentTolerance * degrees},
                        {"worst_first", std::move(worst)}};
}

void addTweakReport(nlohmann::json &report, const TweakResult &tweak, const NetworkAnalysis &repaired,
                    const std::string &output) {
  using nlohmann::json;
  json moves = json::array();
  for (const ControlPointMove &m : tweak.moves)
    moves.push_back({{"vertex", m.vertex},
                     {"curve", m.curve},
                     {"control_point", m.controlPoint},
                     {"parameter", m.parameter},
                     {"distance", m.distance},
                     {"curvature_before", m.curvatureBefore},
                     {"curvature_after", m.curvatureAfter}});
  report["tweak"] = {{"output", output},
                     {"tweaked_vertices", tweak.tweakedVertices},
                     {"inserted_knots", tweak.insertedKnots},
                     {"max_move", tweak.maxMove},
                     {"max_move_relative", tweak.maxMoveRelative},
                     {"moves", std::move(moves)},
                     {"verdict_after", toString(repaired.verdict)},
                     {"max_euler_residual_after", repaired.maxEulerResidualRelative},
                     {"max_enclosure_residual_after", repaired.maxEnclosureResidualRelative}};
}

void printAnalysisTable(const nlohmann::json &report, int maxRows) {
  const auto &vertices = report["vertices"];
  const auto &analysis = report["analysis"];
  std::printf("vertices, worst first (residuals relative to the vertex curvature scale max(|k_i|, 1/diagonal)):\n");
  std::printf("%6s  %-8s %3s %3s %3s  %-16s %10s %10s %9s %11s %11s\n", "vertex", "kind", "val", "ind", "bnd",
              "verdict", "euler", "enclosure", "tangent", "k1", "k2");
  int rows = 0;
  const auto &order = analysis["worst_first"];
  for (const auto &index : order) {
    if (rows++ == maxRows) break;
    const auto &v = vertices.at(index.get<size_t>());
    char enclosure[32];
    if (v["enclosure_applies"].get<bool>())
      std::snprintf(enclosure, sizeof enclosure, "%10.2e", v["enclosure_residual"].get<double>());
    else std::snprintf(enclosure, sizeof enclosure, "%10s", "-");
    std::printf("%6d  %-8s %3d %3d %3s  %-16s %10.2e %s %8.4f° %11.5g %11.5g%s\n", v["index"].get<int>(),
                v["kind"].get<std::string>().c_str(), v["valence"].get<int>(), v["independent_curves"].get<int>(),
                v["boundary"].get<bool>() ? "yes" : "no", v["verdict"].get<std::string>().c_str(),
                v["euler_residual"].get<double>(), enclosure, v["tangent_residual_deg"].get<double>(),
                v["k1"].get<double>(), v["k2"].get<double>(), v["forms_x"].get<bool>() ? "  X" : "");
  }
  if (int(order.size()) > maxRows)
    std::printf("  ... %zu more vertices (--json lists all)\n", order.size() - size_t(maxRows));

  // One line for the network.
  const auto &counts = analysis["vertex_verdicts"];
  const std::string verdict = analysis["verdict"].get<std::string>();
  std::printf("\nverdict: %s (", verdict.c_str());
  bool first = true;
  for (const char *k : {"G2-admissible", "G1-admissible", "needs-tweaking", "no-tangent-plane"})
    if (int c = counts[k].get<int>(); c > 0) std::printf("%s%d %s", first ? "" : ", ", c, k), first = false;
  std::printf("; max Euler residual %.2e, max enclosure residual %.2e)", analysis["max_euler_residual"].get<double>(),
              analysis["max_enclosure_residual"].get<double>());
  if ((verdict == "G1-admissible" || verdict == "needs-tweaking") && !report.contains("tweak"))
    std::printf(" — `curvenet check INPUT --tweak -o FILE.json` repairs the curvatures");
  std::printf("\n");

  if (report.contains("tweak")) {
    const auto &t = report["tweak"];
    std::printf("tweak: %zu vertices, %zu control points moved along the vertex normals (largest move %.3e = %.3e of "
                "the diagonal, %d knots inserted); after: %s, max Euler residual %.2e; written to %s\n",
                t["tweaked_vertices"].size(), t["moves"].size(), t["max_move"].get<double>(),
                t["max_move_relative"].get<double>(), t["inserted_knots"].get<int>(),
                t["verdict_after"].get<std::string>().c_str(), t["max_euler_residual_after"].get<double>(),
                t["output"].get<std::string>().c_str());
  }
}

std::string counted(std::size_t n, const char *one, const char *many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

void printReportTable(const nlohmann::json &report) {
  std::printf("network %s (%s): %s, %s, %s, diagonal %.6g\n", report["name"].get<std::string>().c_str(),
              report["input"].get<std::string>().c_str(),
              counted(report["patches"].get<std::size_t>(), "patch", "patches").c_str(),
              counted(report["segments"].get<std::size_t>(), "segment", "segments").c_str(),
              counted(report["vertices"].size(), "vertex", "vertices").c_str(), report["diagonal"].get<double>());
  std::printf("faces by number of sides:");
  for (auto &[sides, count] : report["faces_by_sides"].items()) std::printf("  %s: %d", sides.c_str(), count.get<int>());
  std::printf("\n\n");
  if (report.contains("analysis")) {
    printAnalysisTable(report);
  } else {
    std::printf("%6s  %-8s %7s %12s %9s\n", "vertex", "kind", "valence", "independent", "boundary");
    for (const auto &v : report["vertices"])
      std::printf("%6d  %-8s %7d %12d %9s\n", v["index"].get<int>(), v["kind"].get<std::string>().c_str(),
                  v["valence"].get<int>(), v["independent_curves"].get<int>(), v["boundary"].get<bool>() ? "yes" : "no");
  }
  if (report.contains("continuity")) {
    const auto &c = report["continuity"];
    std::string kept;
    if (report.contains("kept_g1_faces") && !report["kept_g1_faces"].empty()) {
      kept = "; master faces kept as gregory-g1 patches:";
      for (const auto &f : report["kept_g1_faces"]) kept += " " + std::to_string(f.get<int>());
    }
    std::printf("\ncontinuity (%s%s):\n", report.value("scheme", std::string("?")).c_str(), kept.c_str());
    for (auto &[key, value] : c.items())
      if (value.is_number()) std::printf("  %-28s %.6g\n", key.c_str(), value.get<double>());
  }
  if (report.contains("repair") && !report["repair"]["moves"].empty()) {
    const auto &r = report["repair"];
    std::printf("\nvertex repair (--curves %s): %zu control points moved, largest %.3g of the diagonal (--json lists "
                "every move)\n",
                r["curves"].get<std::string>().c_str(), r["moves"].size(), r["max_move_relative"].get<double>());
  }
  if (report.contains("repair") && !report["repair"].value("skipped", nlohmann::json::array()).empty()) {
    std::printf("\nvertex repair left alone:\n");
    for (const auto &reason : report["repair"]["skipped"]) std::printf("  %s\n", reason.get<std::string>().c_str());
  }
  if (report.contains("shape")) {
    const auto &sh = report["shape"];
    std::string corners;
    for (const auto &c : sh["corner_folds"]) {
      char one[96];
      std::snprintf(one, sizeof one, "%sface %d corner %d (%.2g)", corners.empty() ? "" : "; ", c["face"].get<int>(),
                    c["corner"].get<int>(), c["extent"].get<double>());
      corners += one;
    }
    std::string crossing;
    for (const auto &x : sh["intersections"]) {
      char one[64];
      std::snprintf(one, sizeof one, "%sfaces %d and %d", crossing.empty() ? "" : "; ", x["faces"][0].get<int>(),
                    x["faces"][1].get<int>());
      crossing += one;
    }
    std::printf("\nshape: %zu folded faces, %zu corner folds%s%s%s, %zu face intersections%s%s%s, max excursion %.3g "
                "of the diagonal (face %d, bound %.3g), fairness %.3g (max %.3g, face %d)%s\n",
                sh["folded_faces"].size(), sh["corner_folds"].size(), corners.empty() ? "" : " [",
                corners.c_str(), corners.empty() ? "" : "; extent of the diagonal]", sh["intersections"].size(),
                crossing.empty() ? "" : " [", crossing.c_str(), crossing.empty() ? "" : "]",
                sh["max_excursion"].get<double>(), sh["worst_excursion_face"].get<int>(),
                sh["excursion_bound"].get<double>(), sh["fairness"].get<double>(), sh["max_fairness"].get<double>(),
                sh["worst_fairness_face"].get<int>(), sh["acceptable"].get<bool>() ? "" : " — REJECTED faces listed in --json");
  }
  if (report.contains("composite_faces")) {
    std::printf("\ncomposite faces (split by hidden connection curves; %s):\n",
                counted(report["faces"].get<std::size_t>(), "user face", "user faces").c_str());
    for (const auto &c : report["composite_faces"])
      std::printf("  face %d: %s, %s, max seam curvature jump %.3g%s\n", c["face"].get<int>(),
                  counted(c["patches"].size(), "patch", "patches").c_str(),
                  counted(c["hidden_seams"].size(), "hidden seam", "hidden seams").c_str(),
                  c["max_seam_curvature_jump"].get<double>(),
                  c["folded"].get<bool>() ? ", FOLDED" : "");
  }
  if (report.contains("masters")) {
    std::printf("\nmaster edges (the slave face takes the master's cross curvature; jump as max_curvature_jump):\n");
    for (const auto &m : report["masters"]) {
      const std::string name = m["master_name"].get<std::string>();
      std::printf("  edge %d (curve %d): master face %d%s%s%s, slave face %d, max curvature jump %.3g (mean %.3g)\n",
                  m["edge"].get<int>(), m["curve"].get<int>(), m["master_face"].get<int>(), name.empty() ? "" : " (",
                  name.c_str(), name.empty() ? "" : ")", m["slave_face"].get<int>(),
                  m["max_curvature_jump"].get<double>(), m["mean_curvature_jump"].get<double>());
    }
  }
  if (report.contains("master_surfaces")) {
    std::printf("\nmaster surfaces (each face against the surface its edge names; distance relative to the diagonal, "
                "jump as max_curvature_jump):\n");
    for (const auto &m : report["master_surfaces"])
      std::printf("  edge %d (curve %d): master surface %d, face %d, max distance %.3g, max normal angle %.3g deg, "
                  "max curvature jump %.3g (mean %.3g)\n",
                  m["edge"].get<int>(), m["curve"].get<int>(), m["master_surface"].get<int>(), m["face"].get<int>(),
                  m["max_distance"].get<double>(), m["max_normal_angle_deg"].get<double>(),
                  m["max_curvature_jump"].get<double>(), m["mean_curvature_jump"].get<double>());
  }
  if (report.contains("reference")) {
    std::printf("\nreference deviation (relative to the diagonal):\n");
    for (auto &[key, value] : report["reference"].items())
      if (value.is_number()) std::printf("  %-28s %.6g\n", key.c_str(), value.get<double>());
  }
}

} // namespace curvenet::cli
