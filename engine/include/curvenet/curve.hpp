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
// Cost: construction stores, per non-empty knot span, the span's polynomial
// as Taylor coefficients at both span ends (homogeneous for rational curves),
// O(p) doubles per span and O(p³) work per span. Evaluation of point and
// derivatives up to order 3 is then a span lookup plus O(p) Horner steps
// (degrees above fastDegree use the O(p²) basis-function path), with no heap
// allocation. Curves are immutable values; all const member functions may be
// called concurrently from any number of threads.
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
  /// Highest degree evaluated through the per-span Taylor form; above it
  /// evaluation keeps the basis-function algorithm (the power form's rounding
  /// grows with the degree).
  static constexpr int fastDegree = 10;

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

  /// derivatives() at every t[k] into out[k] (out.size() ≥ t.size()). The
  /// span found for one parameter is tried first for the next, so runs of
  /// sorted parameters cost one span search per run. Results equal those of
  /// derivatives(t[k]) bit for bit.
  void derivatives(std::span<const double> t, std::span<std::array<Vec3, 4>> out) const;

  /// The same as derivatives(t) by the basis-function derivatives of Piegl &
  /// Tiller (Algorithm A2.3) at every call: O(p²), the reference the fast
  /// path is tested against.
  std::array<Vec3, 4> derivativesReference(double t) const;

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
  /// Index into breaks_ of the span holding t (clamped), hint tried first.
  int fastSpan(double t, int hint) const;
  std::array<Vec3, 4> fastDerivatives(double t, int span) const;
  void buildSpans();
  int degree_ = 0;
  std::vector<double> knots_;
  std::vector<Vec3> points_;
  std::vector<double> weights_;
  /// Distinct knots of the domain: span j is [breaks_[j], breaks_[j + 1]].
  std::vector<double> breaks_;
  /// Per span, 2 (p + 1) homogeneous coefficients (x, y, z, w): the Taylor
  /// coefficients C^(k)/k! at the span start, then at its end, so each half
  /// of a span is evaluated near its own expansion point and span ends are
  /// reproduced exactly. Empty above fastDegree.
  std::vector<std::array<double, 4>> taylor_;
};

} // namespace v1
} // namespace curvenet
