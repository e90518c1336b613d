#include "analysis/vertex_curvature.hpp"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <string>

#include "curvenet/error.hpp"

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

// Euler's formula in the harmonic basis: κ(ω) = a + p cos 2ω + q sin 2ω, with
// a the mean and (p, q) the anisotropy. Unlike (W1, W2, W12) these columns
// are orthogonal for evenly spread directions, so their singular values say
// directly which part of the tensor the directions fail to see.
Eigen::RowVector3d harmonicRow(double omega) { return {1.0, std::cos(2 * omega), std::sin(2 * omega)}; }

CurvatureTensor tensorFromHarmonics(const Eigen::Vector3d &x) {
  // W1 = κ(0) = a + p, W2 = κ(π/2) = a − p, W12 = q.
  return CurvatureTensor::fromWeingarten({x(0) + x(1), x(0) - x(1), x(2)});
}

/// |sin| of the angle between the lines of two direction classes: the
/// largest |sin(ω_i − ω_j)| over the pairs (directions within the parallel
/// tolerance are one class, so this is the angle between the two).
double twoCurveSeparation(std::span<const double> omegas, const FitOptions &options) {
  double widest = 0;
  for (std::size_t i = 0; i < omegas.size(); ++i)
    for (std::size_t j = i + 1; j < omegas.size(); ++j) widest = std::max(widest, std::abs(std::sin(omegas[i] - omegas[j])));
  return widest > options.parallelTolerance ? widest : 0.0;
}

bool withinBound(const CurvatureTensor &t, double bound) {
  return std::max(std::abs(t.k1), std::abs(t.k2)) <= bound;
}

} // namespace

double principalCurvatureBound(std::span<const double> ks) {
  if (ks.empty()) return 0;
  const auto [lo, hi] = std::minmax_element(ks.begin(), ks.end());
  return std::max(std::abs(*lo), std::abs(*hi)) + 2 * (*hi - *lo);
}

BoundedCurvatureFit fitBoundedCurvature(std::span<const double> omegas, std::span<const double> ks,
                                        const FitOptions &options) {
  BoundedCurvatureFit out{fitCurvature(omegas, ks, options), 0};
  const double bound = principalCurvatureBound(ks);
  const auto m = Eigen::Index(omegas.size());
  Eigen::MatrixX3d A(m, 3);
  Eigen::VectorXd b(m);
  for (Eigen::Index i = 0; i < m; ++i) A.row(i) = harmonicRow(omegas[i]), b(i) = ks[i];
  const Eigen::JacobiSVD<Eigen::MatrixX3d> svd(A, Eigen::ComputeThinU | Eigen::ComputeThinV);
  const Eigen::Vector3d sigma = svd.singularValues(); // descending
  // Modes the directions determine: a rank-deficient design (n ≤ 2) has
  // fewer, and the paper's n = 2 rules choose the rest; they stand while
  // within the bound.
  int determined = 0;
  for (int i = 0; i < 3; ++i)
    if (sigma(i) > kUndeterminedModeRatio * sigma(0)) ++determined;
  // Three or more curves: kept when every mode is determined and the tensor
  // within the bound. Two: the paper's rules (Sec. 2 (i), App. A) choose the
  // mode the data leave free, and stand unless the curves are nearly
  // parallel (where they divide by a small sin²) and exceed the bound.
  const int n = out.fit.independentDirections;
  const bool inBound = withinBound(out.fit.tensor, bound);
  const bool keep = n >= 3   ? determined == 3 && inBound
                    : n == 2 ? inBound || twoCurveSeparation(omegas, options) >= kNearlyParallelSine
                             : true;
  if (keep) return out;

  // Truncated SVD about the umbilic prior x0 = (mean k, 0, 0): the modes kept
  // fit the data in the least-squares sense, the others keep x0's value.
  const Eigen::Vector3d prior(b.mean(), 0, 0);
  const Eigen::VectorXd misfit = b - A * prior;
  const Eigen::Vector3d projected = svd.matrixU().transpose() * misfit;
  for (int kept = std::min(determined, out.fit.independentDirections); kept >= 0; --kept) {
    Eigen::Vector3d x = prior;
    for (int i = 0; i < kept; ++i) x += svd.matrixV().col(i) * (projected(i) / sigma(i));
    const CurvatureTensor t = tensorFromHarmonics(x);
    if (kept > 0 && !withinBound(t, bound)) continue;
    out.fit.tensor = t;
    out.regularizedModes = 3 - kept;
    break;
  }
  fillResiduals(out.fit, omegas, ks);
  return out;
}

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

double finiteNormalCurvature(double kappa, int vertex, int curve) {
  if (!std::isfinite(kappa))
    throw InputError("", "vertex " + std::to_string(vertex),
                     "curve " + std::to_string(curve) +
                         " has no finite normal curvature there (its derivatives overflow: check its weights and "
                         "control points)");
  return kappa;
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
    ks.push_back(finiteNormalCurvature(dot(d[2], vc.normal) / dot(d[1], d[1]), v, seg.sourceCurve));
  }
  // Two curves meeting smoothly (one loop of a hole, split into arcs; a
  // curve continued by another) leave in directions that agree only to the
  // fit accuracy of the curves. Counted as independent, their tiny angle
  // would turn the difference of their curvatures into a huge twist; the
  // builder's continuation angle (1e-4) decides instead.
  FitOptions fitOptions;
  fitOptions.parallelTolerance = 1e-4;
  const BoundedCurvatureFit bounded = fitBoundedCurvature(omegas, ks, fitOptions);
  const CurvatureFit &fit = bounded.fit;
  vc.regularizedModes = bounded.regularizedModes;
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
