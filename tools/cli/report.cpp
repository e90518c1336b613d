#include "report.hpp"

#include <cstdio>
#include <map>

#include "curvenet/continuity.hpp"

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

void addSurfaceReport(nlohmann::json &report, const Surface &surface, int samplesPerSegment, int resolution) {
  report["scheme"] = schemeName(surface.options().scheme);
  const ContinuityReport c = measureContinuity(surface, {samplesPerSegment});
  report["continuity"] = {{"max_position_gap", c.maxPositionGap},
                          {"max_normal_angle_deg", c.maxNormalAngleDeg},
                          {"mean_normal_angle_deg", c.meanNormalAngleDeg},
                          {"max_boundary_deviation", c.maxBoundaryDeviation},
                          {"worst_normal_segment", c.worstNormalSegment},
                          {"shared_segments", c.sharedSegments},
                          {"samples", c.samples},
                          {"sampling", "every shared segment at u = j/" + std::to_string(samplesPerSegment) +
                                           ", j = 0.." + std::to_string(samplesPerSegment) +
                                           ", from both faces; lengths relative to the diagonal"}};
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

void printReportTable(const nlohmann::json &report) {
  std::printf("network %s (%s): %d patches, %d segments, %zu vertices, diagonal %.6g\n",
              report["name"].get<std::string>().c_str(), report["input"].get<std::string>().c_str(),
              report["patches"].get<int>(), report["segments"].get<int>(), report["vertices"].size(),
              report["diagonal"].get<double>());
  std::printf("faces by number of sides:");
  for (auto &[sides, count] : report["faces_by_sides"].items()) std::printf("  %s: %d", sides.c_str(), count.get<int>());
  std::printf("\n\n%6s  %-8s %7s %12s %9s\n", "vertex", "kind", "valence", "independent", "boundary");
  for (const auto &v : report["vertices"])
    std::printf("%6d  %-8s %7d %12d %9s\n", v["index"].get<int>(), v["kind"].get<std::string>().c_str(),
                v["valence"].get<int>(), v["independent_curves"].get<int>(), v["boundary"].get<bool>() ? "yes" : "no");
  if (report.contains("continuity")) {
    const auto &c = report["continuity"];
    std::printf("\ncontinuity (%s):\n", report.value("scheme", std::string("?")).c_str());
    for (auto &[key, value] : c.items())
      if (value.is_number()) std::printf("  %-28s %.6g\n", key.c_str(), value.get<double>());
  }
  if (report.contains("reference")) {
    std::printf("\nreference deviation (relative to the diagonal):\n");
    for (auto &[key, value] : report["reference"].items())
      if (value.is_number()) std::printf("  %-28s %.6g\n", key.c_str(), value.get<double>());
  }
}

} // namespace curvenet::cli
