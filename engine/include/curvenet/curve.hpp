// curvenet/curve.hpp — B-spline curves, the boundary data of every patch.
//
// A BSplineCurve is a (optionally rational) B-spline of any degree p ≥ 1 on a
// clamped knot vector: the first and last knots have multiplicity p + 1, so the
// curve starts at its first control point and ends at its last. A Bézier curve
// of degree p is the case of p + 1 control points and knots {0…0, 1…1}.
//
// Parameters: the curve is defined on [domainStart(), domainEnd()] = [knot p,
// knot n] of the knot vector. Evaluation outside the domain clamps to it.
//
// Cost: evaluation of point and derivatives up to order 3 is O(p²) with no
// heap allocation for p ≤ maxDegree. Curves are immutable values; all const
// member functions may be called concurrently from any number of threads.
#pragma once

#include <array>
#include <span>
#include <vector>

#include "curvenet/vec.hpp"

namespace curvenet {
inline namespace v1 {

class BSplineCurve {
public:
  /// Highest supported degree (allocation-free evaluation up to it).
  static constexpr int maxDegree = 15;

  BSplineCurve() = default;

  /// Builds a curve; throws InputError (element "curve", with the reason) when
  /// the data are inconsistent: degree outside [1, maxDegree], knot count ≠
  /// points + degree + 1, decreasing or non-clamped knots, a zero-length
  /// domain, non-finite values, or weights that are not positive. Empty
  /// `weights` means a polynomial (non-rational) curve.
  BSplineCurve(int degree, std::vector<double> knots, std::vector<Vec3> controlPoints,
               std::vector<double> weights = {});

  /// The Bézier curve of degree points.size() − 1 on [0, 1].
  static BSplineCurve bezier(std::vector<Vec3> controlPoints);

  int degree() const { return degree_; }
  const std::vector<double> &knots() const { return knots_; }
  const std::vector<Vec3> &controlPoints() const { return points_; }
  /// Empty for polynomial curves.
  const std::vector<double> &weights() const { return weights_; }
  bool isRational() const { return !weights_.empty(); }

  double domainStart() const { return knots_[degree_]; }
  double domainEnd() const { return knots_[knots_.size() - degree_ - 1]; }

  /// Point at parameter t.
  Vec3 point(double t) const;

  /// Point and derivatives with respect to t: result[k] = d^k C / dt^k for
  /// k = 0..3 (derivatives above the degree are zero).
  std::array<Vec3, 4> derivatives(double t) const;

  /// The same curve traversed backwards, on the same domain:
  /// reversed().point(a + b − t) == point(t).
  BSplineCurve reversed() const;

  /// The piece on [from, to] ⊆ domain (from < to), as an exact B-spline by
  /// knot insertion, keeping the original parameterization on [from, to].
  BSplineCurve restricted(double from, double to) const;

  /// The same curve with its parameter mapped affinely so that the domain
  /// becomes [from, to] (from < to). Derivatives scale by the chain rule.
  BSplineCurve reparameterized(double from, double to) const;

  /// Arc length between parameters a and b (Gauss–Legendre per knot span,
  /// adaptive; relative accuracy ≈ 1e-12 for smooth spans).
  double arcLength(double a, double b) const;
  double arcLength() const { return arcLength(domainStart(), domainEnd()); }

  /// Parameter of the curve point closest to p (global over the whole
  /// domain: sampled start, then safeguarded Newton; ends included).
  double closestParameter(const Vec3 &p) const;

  /// Curve interpolating `points` at the parameters `params` (increasing, the
  /// first and last become the domain ends) with the given degree, on the
  /// knot vector chosen by averaging (de Boor), so the system is well posed.
  /// Throws InputError when the data cannot be interpolated.
  static BSplineCurve interpolate(int degree, std::span<const double> params, std::span<const Vec3> points);

private:
  int findSpan(double t) const;
  int degree_ = 0;
  std::vector<double> knots_;
  std::vector<Vec3> points_;
  std::vector<double> weights_;
};

} // namespace v1
} // namespace curvenet
