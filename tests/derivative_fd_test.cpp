// Finite-difference checks of the derivatives the G² ribbons are built from,
// each on its own: the B-spline derivatives up to the third (P‴) and the
// parabolic ribbon's C′ (with P′ and T′). A wrong term here is caught in
// milliseconds, before any ribbon table tries to tabulate it.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "curvenet/builtins.hpp"
#include "curvenet/curve.hpp"
#include "curvenet/network.hpp"
#include "ribbons/ribbons.hpp"

using namespace curvenet;

namespace {

/// Central difference of f at t with step h (error O(h²)).
template <class F> Vec3 centralDifference(F &&f, double t, double h) { return (f(t + h) - f(t - h)) / (2 * h); }

std::vector<BSplineCurve> testCurves() {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coordinate(-1, 1), weight(0.5, 2);
  std::vector<BSplineCurve> curves;
  for (int degree : {3, 4, 5})
    for (bool rational : {false, true}) {
      std::vector<double> knots(static_cast<std::size_t>(degree) + 1, 0.0);
      for (double k : {0.3, 0.55}) knots.push_back(k);
      knots.insert(knots.end(), static_cast<std::size_t>(degree) + 1, 1.0);
      const std::size_t n = knots.size() - static_cast<std::size_t>(degree) - 1;
      std::vector<Vec3> points;
      std::vector<double> weights;
      for (std::size_t k = 0; k < n; ++k) {
        points.push_back({coordinate(rng), coordinate(rng), coordinate(rng)});
        if (rational) weights.push_back(weight(rng));
      }
      curves.emplace_back(degree, knots, points, weights);
    }
  return curves;
}

} // namespace

TEST(DerivativeFiniteDifferences, BSplineDerivativesUpToTheThird) {
  const double h = 1e-5;
  for (const BSplineCurve &curve : testCurves())
    for (double t : {0.1, 0.2, 0.42, 0.7, 0.9}) { // away from the knots 0.3 and 0.55
      const auto d = curve.derivatives(t);
      for (int k = 1; k <= 3; ++k) {
        const Vec3 numeric = centralDifference([&](double u) { return curve.derivatives(u)[k - 1]; }, t, h);
        EXPECT_LE(norm(numeric - d[k]), 1e-5 * (1 + norm(d[k])))
            << "degree " << curve.degree() << (curve.isRational() ? " rational" : "") << " t " << t << ": derivative " << k;
      }
    }
}

TEST(DerivativeFiniteDifferences, ParabolicRibbonCrossCurvatureDerivative) {
  const Network network = Network::build(builtinNetwork("ellipsoid-truncated-icosahedron"));
  const ReferenceSurface &reference = *network.reference();
  for (int e : {0, 7, 31}) {
    const Segment &segment = network.segments()[e];
    const Vec3 side = reference.closest(segment.curve.point(0)).normal;
    auto oriented = [&](const Vec3 &p) {
      const Vec3 n = reference.closest(p).normal;
      return dot(n, side) < 0 ? -n : n;
    };
    const NormalFence fence = NormalFence::fromNormalField(segment.curve, oriented, oriented(segment.curve.point(0)),
                                                           oriented(segment.curve.point(1)));
    std::vector<double> samples;
    for (int j = 0; j <= 32; ++j) {
      const auto c = segment.curve.derivatives(j / 32.0);
      samples.push_back(reference.closest(c[0]).normalCurvature(cross(fence.normal(j / 32.0), c[1])));
    }
    const TransversalCurvature kappa(samples);
    LinearRibbon linear(segment.curve, {{&fence, 0.0, 1.0, false, e}});
    // End conditions that turn T between D and P': α and β vary along the side.
    linear.setEndConditions(linear.fenceDirection(0) + segment.curve.derivatives(0)[1] * 0.4,
                            linear.fenceDirection(1) * 0.7 - segment.curve.derivatives(1)[1] * 0.3);
    const ParabolicRibbon ribbon(linear, {&kappa});
    const double h = 1e-6;
    for (double s : {0.13, 0.31, 0.5, 0.77, 0.9}) {
      const ParabolicJet j = ribbon.at(s);
      const Vec3 dC = centralDifference([&](double u) { return ribbon.at(u).C; }, s, h);
      const Vec3 dT = centralDifference([&](double u) { return ribbon.at(u).T; }, s, h);
      const Vec3 dP = centralDifference([&](double u) { return ribbon.at(u).P; }, s, h);
      EXPECT_LE(norm(dC - j.dC), 1e-6 * norm(j.C) + 1e-7) << "segment " << e << " s " << s << ": C'";
      EXPECT_LE(norm(dT - j.dT), 1e-6 * norm(j.T) + 1e-7) << "segment " << e << " s " << s << ": T'";
      EXPECT_LE(norm(dP - j.dP), 1e-6 * norm(j.dP) + 1e-7) << "segment " << e << " s " << s << ": P'";
    }
  }
}
