// Stroke curves (sketch.hpp step 3): constrained least-squares cubics with
// a fairing term, knots placed by the data.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "graph/welded_graph.hpp"

namespace curvenet {
inline namespace v1 {
namespace graph {
namespace {

constexpr int kDegree = 3;

/// Values and first derivatives of the cubic basis functions nonzero at t:
/// indices first..first+3.
struct BasisAt {
  int first = 0;
  double value[4]{}, derivative[4]{};
};

BasisAt basisAt(const std::vector<double> &knots, int controlPoints, double t) {
  const int p = kDegree;
  int span = p;
  if (t >= knots[controlPoints]) span = controlPoints - 1;
  else span = static_cast<int>(std::upper_bound(knots.begin() + p, knots.begin() + controlPoints + 1, t) - knots.begin()) - 1;
  // Piegl & Tiller A2.3 for derivatives up to order 1.
  double ndu[4][4], left[4], right[4];
  ndu[0][0] = 1;
  for (int j = 1; j <= p; ++j) {
    left[j] = t - knots[span + 1 - j];
    right[j] = knots[span + j] - t;
    double saved = 0;
    for (int r = 0; r < j; ++r) {
      ndu[j][r] = right[r + 1] + left[j - r];
      const double temp = ndu[r][j - 1] / ndu[j][r];
      ndu[r][j] = saved + right[r + 1] * temp;
      saved = left[j - r] * temp;
    }
    ndu[j][j] = saved;
  }
  BasisAt b;
  b.first = span - p;
  for (int j = 0; j <= p; ++j) b.value[j] = ndu[j][p];
  for (int r = 0; r <= p; ++r) {
    double d = 0;
    if (r >= 1) d += ndu[r - 1][p - 1] / ndu[p][r - 1];
    if (r <= p - 1) d -= ndu[r][p - 1] / ndu[p][r];
    b.derivative[r] = d * p;
  }
  return b;
}

/// Clamped knots on [0, 1] with the interior knots at quantiles of the data
/// parameters, so that every span holds about as many points.
std::vector<double> knotsFromData(std::span<const double> parameters, int controlPoints) {
  std::vector<double> knots(kDegree + 1, 0.0);
  const int interior = controlPoints - kDegree - 1;
  const std::size_t m = parameters.size();
  double last = 0;
  for (int j = 1; j <= interior; ++j) {
    const double at = static_cast<double>(j) * static_cast<double>(m - 1) / (interior + 1);
    const std::size_t i = static_cast<std::size_t>(at);
    const double f = at - static_cast<double>(i);
    double knot = i + 1 < m ? parameters[i] * (1 - f) + parameters[i + 1] * f : parameters[m - 1];
    knot = std::clamp(knot, last + 1e-9, 1.0 - 1e-9 * (interior + 1 - j)); // strictly increasing
    knots.push_back(knot);
    last = knot;
  }
  knots.insert(knots.end(), kDegree + 1, 1.0);
  return knots;
}

struct Solved {
  std::vector<Vec3> points;
  double maxError = 0;
};

Solved solve(std::span<const Vec3> data, std::span<const double> parameters, std::span<const FitNode> nodes, bool closed,
             double fairing, const std::vector<double> &knots, int n) {
  // Unknowns: x of all control points, then y, then z (3n).
  const int m = static_cast<int>(data.size());
  Eigen::MatrixXd normal = Eigen::MatrixXd::Zero(n, n);
  Eigen::MatrixXd rhs = Eigen::MatrixXd::Zero(n, 3);
  for (int i = 0; i < m; ++i) {
    const BasisAt b = basisAt(knots, n, parameters[i]);
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) normal(b.first + r, b.first + c) += b.value[r] * b.value[c];
      rhs(b.first + r, 0) += b.value[r] * data[i].x;
      rhs(b.first + r, 1) += b.value[r] * data[i].y;
      rhs(b.first + r, 2) += b.value[r] * data[i].z;
    }
  }
  // Fairing: third differences of the control polygon (its change of
  // turning), scaled with the data so that the weight means the same for any
  // point count. Unlike second differences they barely pull a circle inwards,
  // yet they keep many control points from wiggling between the samples.
  const double w = fairing * m;
  for (int k = 0; k + 3 < n; ++k) {
    const double coef[4] = {-1, 3, -3, 1};
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) normal(k + r, k + c) += w * coef[r] * coef[c];
  }
  // Constraints, rows over the 3n unknowns.
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> values;
  auto positionRows = [&](double t, const Vec3 &p) {
    const BasisAt b = basisAt(knots, n, t);
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::VectorXd row = Eigen::VectorXd::Zero(3 * n);
      for (int r = 0; r < 4; ++r) row(axis * n + b.first + r) = b.value[r];
      rows.push_back(row);
      values.push_back(axis == 0 ? p.x : axis == 1 ? p.y : p.z);
    }
  };
  for (const FitNode &node : nodes) {
    positionRows(node.parameter, node.position);
    if (squaredNorm(node.planeNormal) > 0) {
      const BasisAt b = basisAt(knots, n, node.parameter);
      Eigen::VectorXd row = Eigen::VectorXd::Zero(3 * n);
      const double normal3[3] = {node.planeNormal.x, node.planeNormal.y, node.planeNormal.z};
      for (int axis = 0; axis < 3; ++axis)
        for (int r = 0; r < 4; ++r) row(axis * n + b.first + r) = normal3[axis] * b.derivative[r];
      rows.push_back(row);
      values.push_back(0);
    }
  }
  if (closed) {
    // C'(0) = C'(1): the tangent is continuous where the curve closes.
    const BasisAt b0 = basisAt(knots, n, 0.0), b1 = basisAt(knots, n, 1.0);
    for (int axis = 0; axis < 3; ++axis) {
      Eigen::VectorXd row = Eigen::VectorXd::Zero(3 * n);
      for (int r = 0; r < 4; ++r) row(axis * n + b0.first + r) += b0.derivative[r];
      for (int r = 0; r < 4; ++r) row(axis * n + b1.first + r) -= b1.derivative[r];
      rows.push_back(row);
      values.push_back(0);
    }
  }
  const int k = static_cast<int>(rows.size());
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(3 * n + k, 3 * n + k);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(3 * n + k);
  for (int axis = 0; axis < 3; ++axis) {
    kkt.block(axis * n, axis * n, n, n) = normal;
    b.segment(axis * n, n) = rhs.col(axis);
  }
  for (int r = 0; r < k; ++r) {
    kkt.block(3 * n + r, 0, 1, 3 * n) = rows[r].transpose();
    kkt.block(0, 3 * n + r, 3 * n, 1) = rows[r];
    b(3 * n + r) = values[r];
  }
  const Eigen::VectorXd x = kkt.completeOrthogonalDecomposition().solve(b);
  Solved out;
  out.points.resize(n);
  for (int i = 0; i < n; ++i) out.points[i] = {x(i), x(n + i), x(2 * n + i)};
  for (int i = 0; i < m; ++i) {
    const BasisAt bi = basisAt(knots, n, parameters[i]);
    Vec3 c{0, 0, 0};
    for (int r = 0; r < 4; ++r) c = c + out.points[bi.first + r] * bi.value[r];
    out.maxError = std::max(out.maxError, norm(c - data[i]));
  }
  return out;
}

/// The fitted curve made as fair as the data allow: the fairing weight
/// raised tenfold at a time while the largest error stays within
/// kFairShare of the tolerance (or the fit's own error, where that is
/// larger). With few points per span (a short edge of four samples is
/// interpolated) a hand's wobble otherwise goes straight into the curve's
/// curvature, above all at its ends, where the G² patches take it as
/// boundary data: points 1e-4 of the diagonal off turned the end curvature
/// of bathtub's short edges from ~3 to 30–65 over the diagonal. (Raising a
/// bending term, squared second differences, instead folded more faces.)
void fairToTheData(std::span<const Vec3> points, std::span<const double> parameters, std::span<const FitNode> nodes,
                   bool closed, double tolerance, double fairing, const std::vector<double> &knots, Solved &best) {
  constexpr double kFairShare = 0.25;
  constexpr int kFairSteps = 8;
  const int n = static_cast<int>(knots.size()) - kDegree - 1;
  const double bound = std::max(best.maxError, kFairShare * tolerance);
  double weight = fairing;
  for (int step = 0; step < kFairSteps; ++step) {
    weight *= 10;
    Solved fairer = solve(points, parameters, nodes, closed, weight, knots, n);
    if (!(fairer.maxError <= bound)) break;
    best = std::move(fairer);
  }
}

} // namespace

std::vector<double> chordLengthParameters(std::span<const Vec3> points) {
  std::vector<double> t(points.size(), 0.0);
  for (std::size_t i = 1; i < points.size(); ++i) t[i] = t[i - 1] + norm(points[i] - points[i - 1]);
  const double total = t.back();
  for (double &x : t) x = total > 0 ? x / total : 0.0;
  t.back() = 1.0;
  return t;
}

FittedStroke fitStroke(std::span<const Vec3> points, std::span<const double> parameters, std::span<const FitNode> nodes,
                       bool closed, double tolerance, double fairing) {
  const int m = static_cast<int>(points.size());
  // Enough freedom for the constraints (3 per node, 1 per plane, 3 to close),
  // never more control points than the data can place.
  int constraints = closed ? 3 : 0;
  for (const FitNode &node : nodes) constraints += 3 + (squaredNorm(node.planeNormal) > 0 ? 1 : 0);
  const int most = std::max(kDegree + 1, std::min(m, 400));
  int n = std::clamp(constraints / 3 + 3, kDegree + 1, most);
  Solved best;
  std::vector<double> bestKnots;
  for (;;) {
    const std::vector<double> knots = knotsFromData(parameters, n);
    Solved solved = solve(points, parameters, nodes, closed, fairing, knots, n);
    if (bestKnots.empty() || solved.maxError < best.maxError) best = std::move(solved), bestKnots = knots;
    if (best.maxError <= tolerance || n >= most) break;
    n = std::min(most, n + std::max(2, n / 3));
  }
  fairToTheData(points, parameters, nodes, closed, tolerance, fairing, bestKnots, best);
  FittedStroke out{BSplineCurve(kDegree, bestKnots, best.points), {parameters.begin(), parameters.end()}, best.maxError};
  return out;
}

} // namespace graph
} // namespace v1
} // namespace curvenet
