// BSplineCurve: evaluation against closed forms and finite differences, and
// the exactness of the structural operations (reverse, restrict, reparameterize).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "curvenet/curve.hpp"
#include "curvenet/error.hpp"

using namespace curvenet;

namespace {

void expectNear(const Vec3 &a, const Vec3 &b, double tol) {
  EXPECT_LE(norm(a - b), tol) << "(" << a.x << ", " << a.y << ", " << a.z << ") vs (" << b.x << ", " << b.y << ", "
                              << b.z << ")";
}

// Degree-4 rational curve with non-uniform interior knots, one of them double.
BSplineCurve wavyRational() {
  std::vector<double> U = {0, 0, 0, 0, 0, 0.7, 1.1, 1.1, 1.9, 2.5, 2.5, 2.5, 2.5, 2.5};
  std::vector<Vec3> P = {{0, 0, 0},  {1, 2, 0.5}, {2, -1, 1}, {3, 1, -0.5}, {4, 3, 0},
                         {5, 0, 2}, {6, -2, 1},  {7, 1, 0},   {8, 0, 1}};
  std::vector<double> W = {1, 0.7, 1.6, 0.9, 1.2, 2.0, 0.6, 1.3, 1};
  return BSplineCurve(4, U, P, W);
}

double curvature(const std::array<Vec3, 4> &d) { return norm(cross(d[1], d[2])) / std::pow(norm(d[1]), 3); }

// Rational quadratic arc of radius r, centred at the origin in the xy-plane,
// from angle 0 to `sweep` (< π): middle weight cos(sweep / 2).
BSplineCurve circleArc(double r, double sweep) {
  double h = sweep / 2;
  Vec3 P0{r, 0, 0}, P2{r * std::cos(sweep), r * std::sin(sweep), 0};
  Vec3 P1 = (r / std::cos(h)) * Vec3{std::cos(h), std::sin(h), 0};
  return BSplineCurve(2, {0, 0, 0, 1, 1, 1}, {P0, P1, P2}, {1, std::cos(h), 1});
}

} // namespace

TEST(Curve, BezierReproducesItsPolynomialAndDerivatives) {
  // C(t) = a + b t + c t² + d t³ in Bernstein form.
  Vec3 a{1, -2, 0.5}, b{3, 1, -1}, c{-2, 4, 2}, d{1, -3, 5};
  BSplineCurve curve = BSplineCurve::bezier({a, a + b / 3, a + 2 * b / 3 + c / 3, a + b + c + d});
  EXPECT_EQ(curve.degree(), 3);
  for (double t : {0.0, 0.13, 0.5, 0.77, 1.0}) {
    auto D = curve.derivatives(t);
    expectNear(D[0], a + t * b + t * t * c + t * t * t * d, 1e-13);
    expectNear(curve.point(t), D[0], 1e-14);
    expectNear(D[1], b + 2 * t * c + 3 * t * t * d, 1e-12);
    expectNear(D[2], 2 * c + 6 * t * d, 1e-12);
    expectNear(D[3], 6 * d, 1e-11);
  }
}

TEST(Curve, DerivativesAboveTheDegreeVanish) {
  BSplineCurve quad = BSplineCurve::bezier({{0, 0, 0}, {1, 2, 0}, {2, 0, 1}});
  auto D = quad.derivatives(0.4);
  expectNear(D[3], {}, 1e-14);
  expectNear(D[2], 2 * (Vec3{2, 0, 1} - 2 * Vec3{1, 2, 0}), 1e-13);
}

TEST(Curve, RationalCircleArcHasExactRadiusAndCurvature) {
  for (double sweep : {std::numbers::pi / 2, 2.0, 2.8}) {
    const double r = 1.7;
    BSplineCurve arc = circleArc(r, sweep);
    EXPECT_TRUE(arc.isRational());
    for (int i = 0; i <= 20; ++i) {
      double t = i / 20.0;
      auto D = arc.derivatives(t);
      EXPECT_NEAR(norm(D[0]), r, 1e-13);
      EXPECT_NEAR(dot(D[0], D[1]), 0.0, 1e-12); // tangent ⟂ radius
      EXPECT_NEAR(curvature(D), 1 / r, 1e-11);
    }
  }
}

TEST(Curve, DerivativesMatchCentralFiniteDifferences) {
  BSplineCurve curve = wavyRational();
  const double h = 1e-5;
  // Parameters inside knot spans (the double knot at 1.1 makes d³ jump there).
  for (double t : {0.05, 0.4, 0.9, 1.3, 1.7, 2.2, 2.45}) {
    auto D = curve.derivatives(t), Dp = curve.derivatives(t + h), Dm = curve.derivatives(t - h);
    expectNear(curve.point(t), D[0], 1e-13);
    for (int k = 1; k <= 3; ++k) {
      Vec3 fd = (Dp[k - 1] - Dm[k - 1]) / (2 * h);
      EXPECT_LE(norm(fd - D[k]), 1e-6 * (1 + norm(D[k]))) << "order " << k << " at t = " << t;
    }
  }
}

TEST(Curve, EvaluationClampsToTheDomain) {
  BSplineCurve curve = wavyRational();
  expectNear(curve.point(-1), curve.controlPoints().front(), 1e-15);
  expectNear(curve.point(9), curve.controlPoints().back(), 1e-15);
  expectNear(curve.point(2.5), curve.controlPoints().back(), 1e-14);
}

TEST(Curve, ReversalTraversesBackwards) {
  BSplineCurve curve = wavyRational(), rev = curve.reversed();
  EXPECT_EQ(rev.domainStart(), curve.domainStart());
  EXPECT_EQ(rev.domainEnd(), curve.domainEnd());
  const double s = curve.domainStart() + curve.domainEnd();
  for (double t : {0.0, 0.3, 1.1, 1.5, 2.2, 2.5}) {
    auto D = curve.derivatives(t), R = rev.derivatives(s - t);
    expectNear(R[0], D[0], 1e-12);
    expectNear(R[1], -1.0 * D[1], 1e-10);
    expectNear(R[2], D[2], 1e-9);
  }
}

TEST(Curve, RestrictionKeepsPointsAndParameterization) {
  BSplineCurve curve = wavyRational();
  struct Range {
    double from, to;
  };
  for (Range r : {Range{0.3, 2.0}, Range{0.0, 1.1}, Range{1.1, 2.5}, Range{0.8, 0.9}, Range{0.0, 2.5}}) {
    BSplineCurve piece = curve.restricted(r.from, r.to);
    EXPECT_EQ(piece.domainStart(), r.from);
    EXPECT_EQ(piece.domainEnd(), r.to);
    EXPECT_EQ(piece.isRational(), curve.isRational());
    for (int i = 0; i <= 16; ++i) {
      double t = r.from + (r.to - r.from) * i / 16;
      auto D = curve.derivatives(t), P = piece.derivatives(t);
      expectNear(P[0], D[0], 1e-12);
      expectNear(P[1], D[1], 1e-9 * (1 + norm(D[1])));
    }
    expectNear(piece.controlPoints().front(), curve.point(r.from), 1e-12);
    expectNear(piece.controlPoints().back(), curve.point(r.to), 1e-12);
  }
  // A polynomial curve stays polynomial.
  BSplineCurve poly = BSplineCurve::bezier({{0, 0, 0}, {1, 1, 0}, {2, -1, 0}, {3, 0, 1}});
  BSplineCurve mid = poly.restricted(0.25, 0.6);
  EXPECT_FALSE(mid.isRational());
  EXPECT_EQ(mid.controlPoints().size(), 4u); // a single Bézier piece
  for (double t : {0.25, 0.4, 0.6}) expectNear(mid.point(t), poly.point(t), 1e-14);
}

TEST(Curve, ReparameterizationIsAffine) {
  BSplineCurve curve = wavyRational();
  BSplineCurve re = curve.reparameterized(-1.0, 4.0);
  EXPECT_EQ(re.domainStart(), -1.0);
  EXPECT_EQ(re.domainEnd(), 4.0);
  const double scale = 5.0 / 2.5; // dt'/dt
  for (double t : {0.0, 0.6, 1.1, 2.0, 2.5}) {
    auto D = curve.derivatives(t), R = re.derivatives(-1.0 + scale * t);
    expectNear(R[0], D[0], 1e-12);
    expectNear(R[1], D[1] / scale, 1e-10);
    expectNear(R[2], D[2] / (scale * scale), 1e-9);
  }
}

TEST(Curve, ArcLengthOfLineAndCircle) {
  // A cubic on a straight line with uneven speed: length = chord.
  Vec3 a{1, 2, 3}, b{4, -2, 3};
  BSplineCurve line(3, {0, 0, 0, 0, 0.3, 1, 1, 1, 1}, {a, a + 0.05 * (b - a), a + 0.2 * (b - a), a + 0.9 * (b - a), b});
  EXPECT_NEAR(line.arcLength(), norm(b - a), 1e-12);
  EXPECT_NEAR(line.arcLength(0.2, 0.7), norm(line.point(0.7) - line.point(0.2)), 1e-12);
  EXPECT_NEAR(line.arcLength(0.7, 0.2), line.arcLength(0.2, 0.7), 1e-15);

  const double r = 2.3, sweep = 2.5;
  BSplineCurve arc = circleArc(r, sweep);
  EXPECT_NEAR(arc.arcLength(), r * sweep, 1e-11);
  Vec3 p = arc.point(0.3), q = arc.point(0.8);
  EXPECT_NEAR(arc.arcLength(0.3, 0.8), r * angleBetween(p, q), 1e-11);
}

TEST(Curve, ClosestParameterIsGlobal) {
  const double r = 1.5, sweep = 2.5;
  BSplineCurve arc = circleArc(r, sweep);
  for (double angle : {0.2, 1.0, 2.1}) {
    Vec3 p = 2.0 * Vec3{std::cos(angle), std::sin(angle), 0.3};
    double t = arc.closestParameter(p);
    Vec3 c = arc.point(t);
    EXPECT_NEAR(std::atan2(c.y, c.x), angle, 1e-9);
  }
  // Beyond the ends: the ends themselves.
  EXPECT_EQ(arc.closestParameter({2, -3, 0}), 0.0);
  EXPECT_EQ(arc.closestParameter(3.0 * Vec3{std::cos(3.0), std::sin(3.0), 0}), 1.0);
  // A wavy curve with many local minima: compare with brute-force sampling.
  BSplineCurve curve = wavyRational();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> U(-1, 8);
  for (int k = 0; k < 20; ++k) {
    Vec3 p{U(rng), U(rng) / 2, U(rng) / 4};
    double t = curve.closestParameter(p), best = INFINITY;
    for (int i = 0; i <= 20000; ++i) best = std::min(best, norm(curve.point(2.5 * i / 20000) - p));
    EXPECT_LE(norm(curve.point(t) - p), best + 1e-9);
    // Stationary unless at an end.
    if (t > 0 && t < 2.5) {
      EXPECT_NEAR(dot(curve.derivatives(t)[1], curve.point(t) - p), 0.0, 1e-8);
    }
  }
}

TEST(Curve, InterpolationReproducesDataAndPolynomials) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> U(0.2, 1.0);
  for (int degree : {2, 3, 5}) {
    std::vector<double> params{0.5};
    for (int i = 0; i < 17; ++i) params.push_back(params.back() + U(rng)); // uneven spacing
    // A polynomial of the curve's degree: must come back exactly.
    auto poly = [&](double t) {
      Vec3 v;
      for (int k = 0; k <= degree; ++k) v += std::pow(t - 2, k) * Vec3{1.0 / (k + 1), -0.5 * k, k % 2 ? 0.3 : -0.2};
      return v;
    };
    std::vector<Vec3> pts;
    for (double t : params) pts.push_back(poly(t));
    BSplineCurve c = BSplineCurve::interpolate(degree, params, pts);
    EXPECT_EQ(c.degree(), degree);
    EXPECT_EQ(c.domainStart(), params.front());
    EXPECT_EQ(c.domainEnd(), params.back());
    for (size_t i = 0; i < params.size(); ++i) expectNear(c.point(params[i]), pts[i], 1e-10);
    EXPECT_EQ(c.controlPoints().front(), pts.front());
    EXPECT_EQ(c.controlPoints().back(), pts.back());
    for (int i = 0; i <= 100; ++i) {
      double t = params.front() + (params.back() - params.front()) * i / 100;
      expectNear(c.point(t), poly(t), 1e-8 * norm(poly(t)) + 1e-10);
    }
  }
  // Non-polynomial data: still reproduced at the sites.
  std::vector<double> params;
  std::vector<Vec3> pts;
  for (int i = 0; i <= 12; ++i) {
    params.push_back(i * 0.25);
    pts.push_back({std::cos(i * 0.25), std::sin(i * 0.5), std::exp(-i * 0.1)});
  }
  BSplineCurve c = BSplineCurve::interpolate(4, params, pts);
  for (size_t i = 0; i < params.size(); ++i) expectNear(c.point(params[i]), pts[i], 1e-12);
}

namespace {

template <class F> void expectCurveError(F &&make) {
  try {
    make();
    ADD_FAILURE() << "no InputError thrown";
  } catch (const InputError &e) {
    EXPECT_EQ(e.element(), "curve");
    EXPECT_FALSE(e.reason().empty());
  }
}

} // namespace

TEST(Curve, InvalidInputThrowsInputError) {
  std::vector<Vec3> P = {{0, 0, 0}, {1, 0, 0}, {2, 1, 0}, {3, 0, 0}};
  expectCurveError([&] { BSplineCurve(0, {0, 0, 0, 0, 1, 1, 1, 1}, P); });            // degree 0
  expectCurveError([&] { BSplineCurve(16, std::vector<double>(21, 0), P); });          // degree too high
  expectCurveError([&] { BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1}, P); });               // knot count
  expectCurveError([&] { BSplineCurve(2, {0, 0, 0, 0.7, 0.3, 1, 1}, P); });           // decreasing
  expectCurveError([&] { BSplineCurve(2, {0, 0, 0.1, 0.5, 1, 1, 1}, P); });           // not clamped
  expectCurveError([&] { BSplineCurve(3, {1, 1, 1, 1, 1, 1, 1, 1}, P); });            // zero domain
  expectCurveError([&] { BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1, 1}, {{0, 0, 0}, {NAN, 0, 0}, {1, 1, 1}, {2, 0, 0}}); });
  expectCurveError([&] { BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1, 1}, P, {1, -1, 1, 1}); }); // weight ≤ 0
  expectCurveError([&] { BSplineCurve(3, {0, 0, 0, 0, 1, 1, 1, 1}, P, {1, 1, 1}); });     // weight count
  expectCurveError([&] { BSplineCurve::bezier({{0, 0, 0}}); });
  std::vector<double> t = {0, 1, 1, 2};
  expectCurveError([&] { BSplineCurve::interpolate(2, t, P); });                 // repeated parameter
  std::vector<double> t3 = {0, 1, 2};
  expectCurveError([&] { BSplineCurve::interpolate(2, t3, P); });                // size mismatch
  expectCurveError([&] { BSplineCurve::interpolate(5, std::vector<double>{0, 1, 2, 3}, P); }); // too few
  BSplineCurve ok(3, {0, 0, 0, 0, 1, 1, 1, 1}, P);
  expectCurveError([&] { ok.restricted(0.6, 0.4); });
  expectCurveError([&] { ok.restricted(-0.1, 0.4); });
  expectCurveError([&] { ok.reparameterized(2, 2); });
}

// Found by the network-builder fuzzer: a unit-size curve 2e6 away from the
// origin made the adaptive arc-length rule chase a relative accuracy that
// rounding forbids, for seconds per curve. It must agree with the same curve
// at the origin to the accuracy the coordinates allow, and a cusp inside a
// span must not stall it either.
TEST(BSplineCurve, ArcLengthFarFromTheOriginAndAtACusp) {
  const std::vector<Vec3> near{{0, -2, -2}, {0, -2.2, -2.2}, {0, -2.2, -2.2}, {0, -2, -2}};
  std::vector<Vec3> far = near;
  for (Vec3 &p : far) p.x += 2e6;
  const double reference = BSplineCurve::bezier(near).arcLength();
  EXPECT_NEAR(BSplineCurve::bezier(far).arcLength(), reference, 1e-8 * reference);

  // Cusp at t = 1/2: the speed has a kink there. Compare with a fine polyline.
  const BSplineCurve cusp = BSplineCurve::bezier({{0, 0, 0}, {1, 1, 0}, {0, 1, 0}, {1, 0, 0}});
  double polyline = 0;
  const int steps = 200000;
  for (int k = 0; k < steps; ++k) polyline += norm(cusp.point((k + 1.0) / steps) - cusp.point(double(k) / steps));
  EXPECT_NEAR(cusp.arcLength(), polyline, 1e-8);
}

namespace {

// Random clamped curve of the given degree: 2–6 spans with random lengths,
// interior knots of multiplicity up to the degree, control points in a unit
// box shifted away from the origin, weights in [0.3, 3] when rational.
BSplineCurve randomCurve(std::mt19937 &rng, int degree, bool rational) {
  std::uniform_real_distribution<double> unit(0, 1);
  const int spans = 2 + static_cast<int>(rng() % 5);
  std::vector<double> U(degree + 1, -0.4);
  double knot = -0.4;
  for (int s = 1; s < spans; ++s) {
    knot += 0.05 + unit(rng);
    const int multiplicity = 1 + static_cast<int>(rng() % degree);
    U.insert(U.end(), multiplicity, knot);
  }
  knot += 0.05 + unit(rng);
  U.insert(U.end(), degree + 1, knot);
  const size_t count = U.size() - degree - 1;
  std::vector<Vec3> P(count);
  std::vector<double> W;
  for (Vec3 &q : P) q = Vec3{2 + unit(rng), -1 + unit(rng), unit(rng)};
  if (rational)
    for (size_t i = 0; i < count; ++i) W.push_back(0.3 + 2.7 * unit(rng));
  return BSplineCurve(degree, U, P, W);
}

} // namespace

// The per-span Taylor form agrees with the basis-function algorithm (Piegl &
// Tiller A2.3) to 1e-12 of each derivative's size over the curve, at knots,
// just inside and outside them and at random interior parameters.
TEST(Curve, TaylorFormAgreesWithBasisFunctionDerivatives) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0, 1);
  for (int degree = 1; degree <= BSplineCurve::fastDegree; ++degree)
    for (int rational = 0; rational < 2; ++rational)
      for (int trial = 0; trial < 20; ++trial) {
        const BSplineCurve curve = randomCurve(rng, degree, rational);
        const double a = curve.domainStart(), b = curve.domainEnd();
        std::vector<double> ts;
        for (double u : curve.knots())
          for (double offset : {0.0, -1e-9, 1e-9, -1e-3, 1e-3}) ts.push_back(u + offset * (b - a));
        for (int k = 0; k < 50; ++k) ts.push_back(a + (b - a) * unit(rng));
        std::vector<std::array<Vec3, 4>> reference(ts.size()), fast(ts.size());
        std::array<double, 4> size{};
        for (size_t k = 0; k < ts.size(); ++k) {
          reference[k] = curve.derivativesReference(ts[k]);
          fast[k] = curve.derivatives(ts[k]);
          for (int order = 0; order < 4; ++order) size[order] = std::max(size[order], norm(reference[k][order]));
        }
        for (size_t k = 0; k < ts.size(); ++k)
          for (int order = 0; order < 4; ++order) {
            // Polynomial derivatives above the degree vanish exactly here (the
            // reference leaves rounding residue of the weight sums there).
            if (!rational && order > degree) {
              ASSERT_EQ(fast[k][order], Vec3{});
              continue;
            }
            ASSERT_LE(norm(fast[k][order] - reference[k][order]), 1e-12 * size[order])
                << "degree " << degree << (rational ? " rational" : "") << ", t = " << ts[k] << ", order " << order;
          }
        EXPECT_LE(norm(curve.point(ts.back()) - reference.back()[0]), 1e-12 * size[0]);
      }
}

// Above fastDegree evaluation stays on the reference path; degree 15 works.
TEST(Curve, HighDegreesEvaluate) {
  std::mt19937 rng(3);
  for (int degree : {BSplineCurve::fastDegree + 1, BSplineCurve::maxDegree}) {
    const BSplineCurve curve = randomCurve(rng, degree, true);
    const double t = 0.3 * curve.domainStart() + 0.7 * curve.domainEnd();
    const auto d = curve.derivatives(t), r = curve.derivativesReference(t);
    for (int order = 0; order < 4; ++order) EXPECT_EQ(d[order], r[order]);
    const Vec3 fd = (curve.point(t + 1e-6) - curve.point(t - 1e-6)) / 2e-6;
    EXPECT_LE(norm(fd - d[1]), 1e-6 * norm(d[1]));
  }
}

// Clamped ends are the end control points bit for bit (patch corners and
// shared vertices rely on it), and the batch call equals single calls.
TEST(Curve, EndsExactAndBatchEqualsSingleCalls) {
  std::mt19937 rng(11);
  for (int degree = 1; degree <= 7; ++degree)
    for (int rational = 0; rational < 2; ++rational) {
      const BSplineCurve curve = randomCurve(rng, degree, rational);
      const double a = curve.domainStart(), b = curve.domainEnd();
      // Rational ends are (w P) / w, rounded as the reference rounds them.
      const Vec3 first = curve.derivativesReference(a)[0], last = curve.derivativesReference(b)[0];
      if (!rational) {
        EXPECT_TRUE(first == curve.controlPoints().front() && last == curve.controlPoints().back());
      }
      EXPECT_EQ(curve.point(a), first);
      EXPECT_EQ(curve.point(b), last);
      EXPECT_EQ(curve.derivatives(a)[0], first);
      EXPECT_EQ(curve.derivatives(b)[0], last);
      std::vector<double> ts;
      for (int k = 0; k <= 100; ++k) ts.push_back(a + (b - a) * ((k * 37) % 101) / 100.0); // unsorted runs
      for (int k = 0; k <= 100; ++k) ts.push_back(a + (b - a) * k / 100.0);              // sorted
      std::vector<std::array<Vec3, 4>> batch(ts.size());
      curve.derivatives(ts, batch);
      for (size_t k = 0; k < ts.size(); ++k) EXPECT_EQ(batch[k], curve.derivatives(ts[k])) << ts[k];
    }
}

// A smooth quintic with many short spans far from the origin (the shape of
// the builtins' fitted curves): its derivatives up to the third are
// continuous across the simple knots, and the Taylor form keeps them so to
// 1e-12 of each derivative's size — its coefficients come from differences
// of control points, not from the coordinates (the basis-function path
// leaves jumps of ~4e-10 in the third derivative here).
TEST(Curve, TaylorFormContinuousAcrossKnotsFarFromTheOrigin) {
  std::vector<double> params;
  std::vector<Vec3> points;
  for (int i = 0; i <= 40; ++i) {
    const double t = i / 40.0, angle = 0.6 * t;
    params.push_back(t);
    points.push_back(Vec3{1.0 + 0.45 * std::cos(angle), 0.3 + 0.45 * std::sin(angle), 0.2 * t * t});
  }
  const BSplineCurve curve = BSplineCurve::interpolate(5, params, points);
  std::array<double, 4> size{}, jump{};
  for (size_t i = curve.degree() + 1; i + curve.degree() + 1 < curve.knots().size(); ++i) {
    const double u = curve.knots()[i];
    const auto left = curve.derivatives(std::nextafter(u, -1.0)), right = curve.derivatives(u);
    for (int k = 0; k < 4; ++k)
      size[k] = std::max(size[k], norm(right[k])), jump[k] = std::max(jump[k], norm(left[k] - right[k]));
  }
  for (int k = 0; k < 4; ++k) EXPECT_LE(jump[k], 1e-12 * size[k]) << "order " << k;
}
