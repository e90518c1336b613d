#include "analysis/vertex_curvature.hpp"

#include <cmath>

namespace curvenet {
inline namespace v1 {

namespace {
// A unit x axis in the plane of `normal`, along `hint` where possible.
Vec3 planeAxis(const Vec3 &normal, const Vec3 &hint) {
  Vec3 x = hint - normal * dot(hint, normal);
  if (squaredNorm(x) < 1e-20) {
    const Vec3 any = std::abs(normal.x) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    x = any - normal * dot(any, normal);
  }
  return normalized(x);
}
} // namespace

Vec3 VertexCurvature::direction1() const {
  return xAxis * std::cos(tensor.lambda) + yAxis * std::sin(tensor.lambda);
}

double VertexCurvature::normalCurvature(const Vec3 &v) const {
  const double x = dot(v, xAxis), y = dot(v, yAxis);
  if (x == 0 && y == 0) return 0;
  return tensor.normalCurvature(std::atan2(y, x));
}

Vec3 VertexCurvature::shape(const Vec3 &v) const {
  const Vec3 e1 = direction1(), e2 = direction2();
  return e1 * (tensor.k1 * dot(e1, v)) + e2 * (tensor.k2 * dot(e2, v));
}

std::vector<VertexCurvature> fitVertexCurvatures(const Network &network, const std::vector<VertexFrame> &frames) {
  std::vector<VertexCurvature> result(network.vertices().size());
  for (size_t v = 0; v < network.vertices().size(); ++v) result[v] = fitVertexCurvature(network, frames, static_cast<int>(v));
  return result;
}

VertexCurvature fitVertexCurvature(const Network &network, const std::vector<VertexFrame> &frames, int v) {
  const Vertex &vertex = network.vertices()[v];
  VertexCurvature vc;
  vc.normal = frames[v].normal;
  vc.xAxis = planeAxis(vc.normal, vertex.tangents.empty() ? Vec3{1, 0, 0} : vertex.tangents[0]);
  vc.yAxis = cross(vc.normal, vc.xAxis);
  std::vector<double> omegas, ks;
  for (size_t j = 0; j < vertex.segments.size(); ++j) {
    const Segment &seg = network.segments()[vertex.segments[j]];
    // Which end of the segment is at this vertex: for a closed segment the
    // one whose outgoing tangent is this entry's.
    const auto d0 = seg.curve.derivatives(0.0), d1 = seg.curve.derivatives(1.0);
    bool atStart = seg.start == v;
    if (seg.start == seg.end)
      atStart = dot(normalized(d0[1]), vertex.tangents[j]) >= dot(normalized(-d1[1]), vertex.tangents[j]);
    const auto &d = atStart ? d0 : d1;
    const Vec3 t = vertex.tangents[j];
    omegas.push_back(std::atan2(dot(t, vc.yAxis), dot(t, vc.xAxis)));
    ks.push_back(dot(d[2], vc.normal) / dot(d[1], d[1]));
  }
  // Two curves meeting smoothly (one loop of a hole, split into arcs; a
  // curve continued by another) leave in directions that agree only to the
  // fit accuracy of the curves. Counted as independent, their tiny angle
  // would turn the difference of their curvatures into a huge twist; the
  // builder's continuation angle (1e-4) decides instead.
  FitOptions fitOptions;
  fitOptions.parallelTolerance = 1e-4;
  const CurvatureFit fit = fitCurvature(omegas, ks, fitOptions);
  vc.tensor = fit.tensor;
  vc.branch = fit.branch;
  vc.independentDirections = fit.independentDirections;
  vc.maxResidual = fit.maxResidual;
  return vc;
}

VertexCurvature vertexCurvatureFromReference(const SurfaceFrame &frame, const Vec3 &normal, const Vec3 &xHint) {
  VertexCurvature vc;
  vc.normal = normalized(normal);
  vc.xAxis = planeAxis(vc.normal, xHint);
  vc.yAxis = cross(vc.normal, vc.xAxis);
  const double sign = dot(frame.normal, vc.normal) < 0 ? -1.0 : 1.0;
  // The Weingarten form in (x, y) from S = κ1 e1 e1ᵀ + κ2 e2 e2ᵀ, re-signed.
  const Vec3 e1 = frame.direction1, e2 = cross(frame.normal, frame.direction1);
  auto form = [&](const Vec3 &a, const Vec3 &b) {
    return sign * (frame.k1 * dot(e1, a) * dot(e1, b) + frame.k2 * dot(e2, a) * dot(e2, b));
  };
  vc.tensor = CurvatureTensor::fromWeingarten({form(vc.xAxis, vc.xAxis), form(vc.yAxis, vc.yAxis),
                                               form(vc.xAxis, vc.yAxis)});
  vc.independentDirections = 3;
  return vc;
}

} // namespace v1
} // namespace curvenet
