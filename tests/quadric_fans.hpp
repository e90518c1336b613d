// Test networks with known vertex curvatures: fans of exact surface curves on
// a quadric graph, optionally with one curve's curvature perturbed.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet::test {

// z = f(x, y) = a x² + b y² + c x y. Over a straight line in the xy-plane f is
// a quadratic, so every curve below is an exact surface curve: a quadratic
// Bézier elevated to a cubic.

struct Quadric {
  double a = 0.3, b = -0.2, c = 0.15;
  double f(double x, double y) const { return a * x * x + b * y * y + c * x * y; }
  Vec3 lift(double x, double y) const { return {x, y, f(x, y)}; }
  double fx(double x, double y) const { return 2 * a * x + c * y; }
  double fy(double x, double y) const { return 2 * b * y + c * x; }
  /// Upward unit normal and principal curvatures (k1 ≥ k2) at (x, y).
  std::pair<double, double> principal(double x, double y) const {
    const double gx = fx(x, y), gy = fy(x, y), W = std::sqrt(1 + gx * gx + gy * gy);
    Eigen::Matrix2d I, II;
    I << 1 + gx * gx, gx * gy, gx * gy, 1 + gy * gy;
    II << 2 * a / W, c / W, c / W, 2 * b / W;
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> solver(II, I);
    return {solver.eigenvalues()(1), solver.eigenvalues()(0)};
  }
  /// The surface curve over the segment A → B of the xy-plane, as a cubic Bézier.
  BSplineCurve over(double ax, double ay, double bx, double by) const {
    const double dx = bx - ax, dy = by - ay;
    const Vec3 P0 = lift(ax, ay), P2 = lift(bx, by);
    const Vec3 P1{ax + 0.5 * dx, ay + 0.5 * dy, f(ax, ay) + 0.5 * (fx(ax, ay) * dx + fy(ax, ay) * dy)};
    return BSplineCurve::bezier({P0, (P0 + 2 * P1) / 3, (2 * P1 + P2) / 3, P2});
  }
};

/// Rescales a cubic Bézier's inner legs (tangent directions kept): changes
/// the curvature at both ends, nothing else of first order.
inline BSplineCurve bentLegs(const BSplineCurve &c, double alpha, double beta) {
  auto Q = c.controlPoints();
  Q[1] = Q[0] + alpha * (Q[1] - Q[0]);
  Q[2] = Q[3] + beta * (Q[2] - Q[3]);
  return BSplineCurve::bezier(Q);
}

struct FanSpec {
  double cx = 0, cy = 0, radius = 1;
  std::vector<double> anglesDeg;   ///< increasing, gaps < 180°
  int throughPair = -1;            ///< ends i and i + n/2 form one curve through the centre (angles opposite)
  std::vector<double> legScale;    ///< per end: β applied to its curve (1 = exact)
};

/// Adds a fan (triangles centre, p_i, p_{i+1}) to `net`.
inline void addFan(NetworkDescription &net, const Quadric &q, const FanSpec &fan) {
  const int n = int(fan.anglesDeg.size());
  std::vector<double> px(n), py(n);
  for (int i = 0; i < n; ++i) {
    const double t = fan.anglesDeg[i] * std::numbers::pi / 180;
    px[i] = fan.cx + fan.radius * std::cos(t), py[i] = fan.cy + fan.radius * std::sin(t);
  }
  // side (curve, from, to) running from the centre out to p_i
  std::vector<SideDescription> out(n);
  const int opposite = fan.throughPair >= 0 ? fan.throughPair + n / 2 : -1;
  if (fan.throughPair >= 0) {
    const int i = fan.throughPair;
    net.curves.push_back(q.over(px[i], py[i], px[opposite], py[opposite]));
    const int id = int(net.curves.size()) - 1;
    out[i] = {id, 0.5, 0.0};
    out[opposite] = {id, 0.5, 1.0};
  }
  for (int i = 0; i < n; ++i) {
    if (i == fan.throughPair || i == opposite) continue;
    BSplineCurve radial = q.over(fan.cx, fan.cy, px[i], py[i]);
    const double beta = fan.legScale.empty() ? 1.0 : fan.legScale[i];
    if (beta != 1.0) radial = bentLegs(radial, 1.0, beta);
    net.curves.push_back(radial);
    out[i] = {int(net.curves.size()) - 1, 0.0, 1.0};
  }
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    net.curves.push_back(q.over(px[i], py[i], px[j], py[j]));
    const int chord = int(net.curves.size()) - 1;
    const SideDescription back{out[j].curve, out[j].to, out[j].from};
    net.faces.push_back({{out[i], {chord, 0.0, 1.0}, back}, ""});
  }
}

} // namespace curvenet::test
