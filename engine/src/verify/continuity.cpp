// Continuity and deviation figures (see curvenet/continuity.hpp).
#include "curvenet/continuity.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "curvenet/error.hpp"
#include "curvenet/tessellate.hpp"
#include "parallel/fork_join.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

/// Where a segment lies on a face: its side and the side-parameter range.
struct SegmentOnFace {
  int face, side;
  double from, to; ///< side parameters at the segment's u = 0 and u = 1
};

std::vector<SegmentOnFace> placesOf(const Network &net, int segment) {
  std::vector<SegmentOnFace> places;
  const auto &faces = net.segments()[segment].faces;
  for (int slot = 0; slot < 2; ++slot) {
    const int f = faces[slot];
    if (f < 0 || (slot == 1 && f == faces[0])) continue; // a face using the segment twice is searched once
    const Face &face = net.faces()[f];
    for (int k = 0; k < face.sideCount(); ++k) {
      const FaceSide &side = face.sides[k];
      for (size_t j = 0; j < side.segments.size(); ++j) {
        if (side.segments[j] != segment) continue;
        const double b0 = j == 0 ? 0.0 : side.breaks[j - 1];
        const double b1 = j + 1 == side.segments.size() ? 1.0 : side.breaks[j];
        places.push_back(side.segmentReversed[j] ? SegmentOnFace{f, k, b1, b0} : SegmentOnFace{f, k, b0, b1});
      }
    }
  }
  return places;
}

double angleDegrees(const Vec3 &a, const Vec3 &b) {
  return std::atan2(norm(cross(a, b)), dot(a, b)) * 180.0 / std::numbers::pi;
}

struct SegmentFigures {
  double gap = 0, maxAngle = 0, sumAngle = 0, boundary = 0;
  std::size_t samples = 0;
};

} // namespace

ContinuityReport measureContinuity(const Surface &surface, const ContinuityOptions &options) {
  if (options.samplesPerSegment < 1) throw InputError("", "samples per segment", "must be at least 1");
  const Network &net = surface.network();
  const int m = options.samplesPerSegment;
  const double diagonal = net.diagonal();
  const int segments = static_cast<int>(net.segments().size());
  std::vector<SegmentFigures> figures(segments);
  std::vector<char> shared(segments, 0);

  parallel::parallelFor(0, segments, [&](int e) {
    const std::vector<SegmentOnFace> places = placesOf(net, e);
    SegmentFigures &fig = figures[e];
    const BSplineCurve &curve = net.segments()[e].curve;
    for (int j = 0; j <= m; ++j) {
      const double u = double(j) / m;
      const Vec3 onCurve = curve.point(u);
      std::vector<SurfacePoint> seen;
      for (const SegmentOnFace &p : places) {
        const double s = p.from + (p.to - p.from) * u;
        seen.push_back(surface.evaluate(p.face, surface.domainPointOnFaceSide(p.face, p.side, s)));
        fig.boundary = std::max(fig.boundary, norm(seen.back().point - onCurve));
      }
      if (places.size() != 2) continue;
      shared[e] = 1;
      // Faces running the segment in opposite directions (the consistent,
      // orientable case) have normals on the same side of the surface.
      const bool sameDirection = (places[0].to > places[0].from) == (places[1].to > places[1].from);
      const Vec3 other = sameDirection ? -seen[1].normal : seen[1].normal;
      const double angle = angleDegrees(seen[0].normal, other);
      fig.gap = std::max(fig.gap, norm(seen[0].point - seen[1].point));
      fig.maxAngle = std::max(fig.maxAngle, angle);
      fig.sumAngle += angle;
      ++fig.samples;
    }
  });

  ContinuityReport report;
  report.samplesPerSegment = m;
  double sumAngle = 0;
  for (int e = 0; e < segments; ++e) {
    const SegmentFigures &fig = figures[e];
    report.maxBoundaryDeviation = std::max(report.maxBoundaryDeviation, fig.boundary / diagonal);
    if (!shared[e]) continue;
    ++report.sharedSegments;
    report.maxPositionGap = std::max(report.maxPositionGap, fig.gap / diagonal);
    if (surface.isCreaseSegment(e)) {
      ++report.creaseSegments;
      continue;
    }
    report.samples += fig.samples;
    sumAngle += fig.sumAngle;
    if (report.worstNormalSegment < 0 || fig.maxAngle > report.maxNormalAngleDeg) {
      report.maxNormalAngleDeg = fig.maxAngle;
      report.worstNormalSegment = e;
    }
  }
  if (report.samples > 0) report.meanNormalAngleDeg = sumAngle / static_cast<double>(report.samples);
  return report;
}

std::optional<ReferenceDeviation> measureReferenceDeviation(const Surface &surface, int resolution, int threads) {
  const Network &net = surface.network();
  if (!net.reference()) return std::nullopt;
  const ReferenceSurface &reference = *net.reference();
  const Mesh mesh = tessellate(surface, {resolution, threads});
  std::vector<double> distance(mesh.positions.size());
  parallel::parallelFor(std::size_t(0), mesh.positions.size(),
                    [&](std::size_t i) { distance[i] = reference.signedDistance(mesh.positions[i]); });
  ReferenceDeviation result;
  result.resolution = resolution;
  result.samples = distance.size();
  const double diagonal = net.diagonal();
  double sum = 0;
  for (double d : distance) {
    result.maxDeviation = std::max(result.maxDeviation, std::abs(d) / diagonal);
    result.minSigned = std::min(result.minSigned, d / diagonal);
    result.maxSigned = std::max(result.maxSigned, d / diagonal);
    sum += std::abs(d);
  }
  if (!distance.empty()) result.meanDeviation = sum / static_cast<double>(distance.size()) / diagonal;
  return result;
}

} // namespace v1
} // namespace curvenet
