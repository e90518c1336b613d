// Curvature jump across shared edges (curvenet/curvature_jump.hpp).
#include "curvenet/curvature_jump.hpp"

#include <algorithm>
#include <cmath>

#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

CurvatureJumpReport measureCurvatureJump(const Surface &surface, const CurvatureJumpOptions &options) {
  if (options.samplesPerSegment < 2) throw InputError("", "samplesPerSegment", "must be at least 2");
  if (!(options.endExclusion >= 0 && options.endExclusion < 0.5))
    throw InputError("", "endExclusion", "must lie in [0, 0.5)");
  const Network &network = surface.network();
  const double floor = 1.0 / network.diagonal();
  // Within endExclusion of a domain side's length from a domain corner: the
  // segment ends, and the split points of 2-sided faces (domain corners too).
  auto nearCorner = [&](int face, const Vec2 &uv) {
    const int n = surface.domainSides(face);
    const double limit = options.endExclusion * norm(surface.domainCorner(face, 1) - surface.domainCorner(face, 0));
    for (int k = 0; k < n; ++k)
      if (norm(uv - surface.domainCorner(face, k)) < limit * (1 - 1e-9)) return true;
    return false;
  };
  CurvatureJumpReport report;
  double sum = 0;
  for (size_t e = 0; e < network.segments().size(); ++e) {
    const Segment &seg = network.segments()[e];
    if (seg.isBoundary()) continue;
    for (int j = 0; j < options.samplesPerSegment; ++j) {
      const double u = options.endExclusion +
                       (1 - 2 * options.endExclusion) * double(j) / (options.samplesPerSegment - 1);
      const Vec2 uvA = surface.domainPointOnSegment(seg.faces[0], int(e), u);
      const Vec2 uvB = surface.domainPointOnSegment(seg.faces[1], int(e), u);
      if (nearCorner(seg.faces[0], uvA) || nearCorner(seg.faces[1], uvB)) continue;
      const SurfacePoint2 a = surface.evaluateSecondOrder(seg.faces[0], uvA, options.step);
      const SurfacePoint2 b = surface.evaluateSecondOrder(seg.faces[1], uvB, options.step);
      // The common transversal direction N × P' (either sign gives the same κ).
      const Vec3 direction = cross(a.normal, seg.curve.derivatives(u)[1]);
      CurvatureJumpSample sample;
      sample.segment = int(e);
      sample.u = u;
      sample.kappaA = a.normalCurvature(direction);
      sample.kappaB = (dot(a.normal, b.normal) < 0 ? -1.0 : 1.0) * b.normalCurvature(direction);
      sample.jump = std::abs(sample.kappaA - sample.kappaB) /
                    std::max({std::abs(sample.kappaA), std::abs(sample.kappaB), floor});
      sum += sample.jump;
      if (sample.jump > report.maxJump || report.worstSegment < 0) {
        report.maxJump = sample.jump;
        report.worstSegment = sample.segment;
        report.worstU = u;
      }
      report.samples.push_back(sample);
    }
  }
  if (!report.samples.empty()) report.meanJump = sum / double(report.samples.size());
  return report;
}

std::vector<MasterEdgeJump> masterEdgeJumps(const Surface &surface, const CurvatureJumpReport &report) {
  const Network &network = surface.network();
  std::vector<MasterEdgeJump> masters;
  std::vector<int> slot(network.segments().size(), -1);
  for (size_t e = 0; e < network.segments().size(); ++e) {
    const Segment &seg = network.segments()[e];
    if (seg.masterFace < 0 || seg.isBoundary()) continue;
    slot[e] = static_cast<int>(masters.size());
    masters.push_back({int(e), seg.sourceCurve, seg.masterFace, seg.faces[0] == seg.masterFace ? seg.faces[1] : seg.faces[0]});
  }
  for (const CurvatureJumpSample &sample : report.samples) {
    if (sample.segment < 0 || size_t(sample.segment) >= slot.size() || slot[size_t(sample.segment)] < 0) continue;
    MasterEdgeJump &m = masters[size_t(slot[size_t(sample.segment)])];
    m.maxJump = std::max(m.maxJump, sample.jump);
    m.meanJump += sample.jump;
    ++m.samples;
  }
  for (MasterEdgeJump &m : masters)
    if (m.samples > 0) m.meanJump /= m.samples;
  return masters;
}

} // namespace v1
} // namespace curvenet
