// Kernels: every SIMD width against the width-1 reference (1e-12 relative),
// the reference against plain scalar formulas, and the batched sweepline
// solver against an independent one (companion-matrix eigenvalues).
//
// The solver comparison runs 10⁵ random domain points per n = 3..8; set
// CURVENET_LONG_TESTS=1 for the full 10⁶ per n (about a minute).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include "curvenet/kernels/kernels.hpp"
#include "patches/domain.hpp"
#include "patches/patch.hpp"

using namespace curvenet;
namespace ck = curvenet::kernels;

namespace {

struct Soa {
  std::vector<double> data;
  explicit Soa(size_t arrays, size_t count, std::mt19937_64 *rng = nullptr) : data(arrays * count), count_(count) {
    if (rng) {
      std::uniform_real_distribution<double> u(-2, 2);
      for (double &x : data) x = u(*rng);
    }
  }
  double *operator[](size_t a) { return data.data() + a * count_; }
  size_t count_;
};

ck::DualVec3Span span9(Soa &s, size_t base = 0) {
  return {{s[base + 0], s[base + 1], s[base + 2]}, {s[base + 3], s[base + 4], s[base + 5]},
          {s[base + 6], s[base + 7], s[base + 8]}};
}

double relativeDifference(const std::vector<double> &a, const std::vector<double> &b) {
  double scale = 0, diff = 0;
  for (size_t i = 0; i < a.size(); ++i) scale = std::max(scale, std::abs(b[i])), diff = std::max(diff, std::abs(a[i] - b[i]));
  return diff / std::max(scale, 1e-300);
}

constexpr size_t kCount = 1003; // not a multiple of any width: tails are exercised

TEST(Kernels, WidthsIncludeReferenceAndBest) {
  const auto widths = ck::availableWidths();
  ASSERT_GE(widths.size(), 2u);
  EXPECT_EQ(widths.front().lanes, 1u);
  EXPECT_GE(ck::bestWidth().lanes, 1u);
  for (const auto &w : widths) std::printf("kernel width %s: %zu lanes\n", w.name.c_str(), w.lanes);
}

// ---- sweepline solver ------------------------------------------------------

struct SideFrame {
  ck::SweepFrame frame;
  Vec2 p0, e;
};

/// Side 0 of the regular n-gon: its sweep constants and its frame's origin and direction.
SideFrame sideZeroFrame(int n) {
  const RegularDomain domain(n);
  return {domain.sweepFrame(0), domain.corner(0), domain.corner(1) - domain.corner(0)};
}

/// `count` uniformly random points strictly inside the regular n-gon, in
/// side 0's frame (x along the side, y the distance into the domain).
void randomInteriorPoints(int n, std::size_t count, std::mt19937_64 &rng, std::vector<double> &x,
                          std::vector<double> &y) {
  const RegularDomain domain(n);
  const SideFrame side = sideZeroFrame(n);
  std::uniform_real_distribution<double> u(-1, 1);
  while (x.size() < count) {
    const Vec2 q{u(rng), u(rng)};
    bool inside = true;
    for (int i = 0; i < n && inside; ++i) inside = domain.perpendicularDistance(i, q.x, q.y).v > 0;
    if (!inside) continue;
    const Vec2 r = q - side.p0;
    x.push_back(dot(r, side.e) / dot(side.e, side.e));
    y.push_back(cross(side.e, r) / dot(side.e, side.e));
  }
}

/// Independent solver: F from its definition (H(1 − s) evaluated as such),
/// its power-basis coefficients by interpolation at five nodes, the real
/// roots as companion-matrix eigenvalues, polished by Newton on F itself;
/// then the same candidate rule.
double independentRoot(const ck::SweepFrame &f, double x, double y) {
  auto H = [](double s) { return 2 * s * s * s - 3 * s * s + 1; };
  auto w = [&](double s, double &wx, double &wy) {
    wx = f.ax * H(s) + f.bx * H(1 - s);
    wy = f.ay * H(s) + f.by * H(1 - s);
  };
  auto F = [&](double s) {
    double wx, wy;
    w(s, wx, wy);
    return (x - s) * wy - y * wx;
  };
  Eigen::Matrix<double, 5, 5> V;
  Eigen::Matrix<double, 5, 1> rhs;
  for (int i = 0; i < 5; ++i) {
    const double s = i / 4.0;
    for (int j = 0; j < 5; ++j) V(i, j) = std::pow(s, j);
    rhs(i) = F(s);
  }
  Eigen::Matrix<double, 5, 1> coef = V.fullPivLu().solve(rhs);
  int degree = 4;
  const double scale = coef.cwiseAbs().maxCoeff();
  while (degree > 0 && std::abs(coef(degree)) <= 1e-11 * scale) --degree;
  std::vector<double> roots;
  if (degree >= 1) {
    using Companion = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, 4, 4>;
    Companion companion = Companion::Zero(degree, degree);
    for (int i = 1; i < degree; ++i) companion(i, i - 1) = 1;
    for (int i = 0; i < degree; ++i) companion(i, degree - 1) = -coef(i) / coef(degree);
    Eigen::EigenSolver<Companion> solver(companion, false);
    for (int i = 0; i < degree; ++i) {
      const std::complex<double> r = solver.eigenvalues()(i);
      if (std::abs(r.imag()) > 1e-6 || r.real() < -1e-7 || r.real() > 1 + 1e-7) continue;
      double s = std::clamp(r.real(), 0.0, 1.0);
      for (int it = 0; it < 3; ++it) {
        const double h = 1e-7, slope = (F(std::min(1.0, s + h)) - F(std::max(0.0, s - h))) /
                                       (std::min(1.0, s + h) - std::max(0.0, s - h));
        if (slope != 0) s = std::clamp(s - F(s) / slope, 0.0, 1.0);
      }
      roots.push_back(s);
    }
  }
  const double radial = f.parallel ? x - y * f.ax / f.ay : f.apexX - f.apexY * (x - f.apexX) / (y - f.apexY);
  double best = -1, bestScore = INFINITY;
  for (double s : roots) {
    double wx, wy;
    w(s, wx, wy);
    const double dH = 6 * s * s - 6 * s;
    const double sx = (f.ax - f.bx) * dH, sy = (f.ay - f.by) * dH;
    const double d = std::abs(wx) > std::abs(wy) ? (x - s) / wx : y / wy;
    const double jac = (1 + d * sx) * wy - d * sy * wx;
    const double score = std::abs(s - radial) + (jac > 1e-9 ? 0 : 2);
    if (d >= -1e-9 && score < bestScore) bestScore = score, best = s;
  }
  return best < 0 ? std::clamp(x, 0.0, 1.0) : best;
}

TEST(Kernels, SweepSolverMatchesEigenvaluesScalarSolverAndAcrossWidths) {
  const char *longRun = std::getenv("CURVENET_LONG_TESTS");
  const size_t count = longRun && std::string(longRun) == "1" ? 1000000 : 100000;
  std::mt19937_64 rng(3);
  for (int n = 3; n <= 8; ++n) {
    const RegularDomain domain(n);
    std::vector<double> x, y;
    randomInteriorPoints(n, count, rng, x, y);
    const SideFrame side = sideZeroFrame(n);
    std::vector<double> sRef(count), dRef(count);
    ck::hermiteSweepRoots(count, side.frame, x.data(), y.data(), sRef.data(), dRef.data(), ck::kScalarReference);
    for (const auto &w : ck::availableWidths()) {
      std::vector<double> s(count), d(count);
      ck::hermiteSweepRoots(count, side.frame, x.data(), y.data(), s.data(), d.data(), w.id);
      EXPECT_LE(relativeDifference(s, sRef), 1e-12) << w.name << " n=" << n;
      EXPECT_LE(relativeDifference(d, dRef), 1e-12) << w.name << " n=" << n;
    }
    // Against the companion-matrix solver: the same root to 1e-8 (roots near
    // the triangle's fold are double, so only ~√ε accurate there).
    size_t mismatches = 0;
    double worst = 0;
    for (size_t k = 0; k < count; ++k) {
      const double s = independentRoot(side.frame, x[k], y[k]);
      const double e = std::abs(s - sRef[k]);
      worst = std::max(worst, e);
      if (e > 1e-8) ++mismatches;
      // Every point lies on its sweepline: (x, y) = (s, 0) + d w(s).
      const double H = 2 * std::pow(sRef[k], 3) - 3 * sRef[k] * sRef[k] + 1;
      const double wx = side.frame.bx + (side.frame.ax - side.frame.bx) * H,
                   wy = side.frame.by + (side.frame.ay - side.frame.by) * H;
      ASSERT_NEAR(sRef[k] + dRef[k] * wx, x[k], 1e-9) << "n=" << n;
      ASSERT_NEAR(dRef[k] * wy, y[k], 1e-9) << "n=" << n;
    }
    std::printf("n=%d: %zu points, %zu disagreements with the eigenvalue solver, worst %.2e\n", n, count, mismatches,
                worst);
    EXPECT_EQ(mismatches, 0u) << "n=" << n;
    // And against the engine's scalar grid-and-bisection solver (side 0).
    for (size_t k = 0; k < count; k += 97) {
      const Vec2 q = side.p0 + side.e * x[k] + Vec2{-side.e.y, side.e.x} * y[k];
      const double s = domain.hermiteSweepByGrid(0, Dual::u(q.x), Dual::vCoord(q.y)).s.v;
      EXPECT_NEAR(s, sRef[k], 1e-8) << "n=" << n << " at " << q.x << "," << q.y;
    }
  }
}

} // namespace

namespace {

/// Random inputs of the Gregory position kernel: parameters and blends in
/// [0, 1], ribbon values and corner vectors in [−2, 2], and a sample at
/// corner 1 (s_1 = 0, s_0 = 1: the rational weights' limit) and one very
/// near it (the batch inversion's underflow fallback). With `shares`, the
/// corners take blend shares 1, 0 and random ones in between; with
/// `reaches` (G²), the ribbons saturating reaches (saturatingReaches).
struct RandomGregoryInput {
  Soa s, blend, P, T, C;
  ck::GregorySamples in;
  std::vector<ck::GregoryCorner> corners;
  RandomGregoryInput(int n, bool parabolic, std::mt19937_64 &rng, bool shares = false, bool reaches = false)
      : s(n, kCount), blend(n, kCount), P(3 * n, kCount, &rng), T(3 * n, kCount, &rng), C(3 * n, kCount, &rng),
        corners(n) {
    std::uniform_real_distribution<double> unit(0, 1), u(-2, 2);
    for (double &x : s.data) x = unit(rng);
    for (double &x : blend.data) x = unit(rng);
    s[1][5] = 0, s[0][5] = 1, s[1][6] = 1e-90, s[0][6] = 1 - 1e-16;
    in.sides = n, in.parabolic = parabolic;
    for (int i = 0; i < n; ++i) {
      in.s[i] = s[i], in.blend[i] = blend[i];
      for (int c = 0; c < 3; ++c) in.P[i][c] = P[3 * i + c], in.T[i][c] = T[3 * i + c], in.C[i][c] = C[3 * i + c];
    }
    for (auto &corner : corners)
      for (auto &v : corner.v)
        for (double &x : v) x = u(rng);
    if (shares)
      for (int i = 0; i < n; ++i) in.blendShare[i] = i == 0 ? 1.0 : i == 1 ? 0.0 : unit(rng);
    if (reaches) saturatingReaches(n, rng, in.reach);
  }
  /// Ribbon reaches as the engine takes them (0.05 … 1, 1 meaning none):
  /// ribbon 0 at the floor, ribbon 1 unsaturated, the rest random, so that
  /// corners see both, one or neither of their ribbons saturate.
  static void saturatingReaches(int n, std::mt19937_64 &rng, double *reach) {
    std::uniform_real_distribution<double> unit(0.05, 1.2);
    for (int i = 0; i < n; ++i) reach[i] = i == 0 ? 0.05 : i == 1 ? 1.0 : std::min(unit(rng), 1.0);
  }
};

/// A saturated cross parameter r tanh(d / r) (r ≥ 1: d), the engine's formula.
double saturated(double d, double reach) { return reach >= 1 ? d : reach * std::tanh(d / reach); }

/// The two-ribbon blend's weight t^m / (s^m + t^m) of R_{i−1} at a corner
/// (m = 3 for G², 2 for G¹), ½ at the corner.
double sideBlendWeight(double s, double t, int m) {
  const double sm = std::pow(s, m), tm = std::pow(t, m);
  return sm + tm <= 1e-250 ? 0.5 : tm / (sm + tm);
}

/// Gregory positions by the formula with plain divisions (no batch inversion).
std::array<double, 3> gregoryFormula(const ck::GregorySamples &in, const ck::GregoryCorner *corners, size_t k) {
  std::array<double, 3> out{};
  const int n = in.sides;
  for (int i = 0; i < n; ++i) {
    const int prev = (i + n - 1) % n;
    // The blends take the sweep's (s, t); the ribbons' distances and the
    // correction patch the saturated pair (sc, tc) (G² only).
    const double s = in.s[i][k], t = 1 - in.s[prev][k], b = in.blend[i][k];
    const double sc = in.parabolic ? saturated(s, in.reach[prev]) : s, tc = in.parabolic ? saturated(t, in.reach[i]) : t;
    const double(*v)[3] = corners[i].v;
    auto w = [](double x, double y) { return x + y == 0 ? 0.5 : x / (x + y); };
    for (int c = 0; c < 3; ++c) {
      double left = in.P[prev][c][k] + sc * in.T[prev][c][k], right = in.P[i][c][k] + tc * in.T[i][c][k];
      double q = v[0][c];
      if (in.parabolic) {
        left += 0.5 * sc * sc * in.C[prev][c][k], right += 0.5 * tc * tc * in.C[i][c][k];
        const double sp[4] = {1, sc, sc * sc, sc * sc * sc}, tp[4] = {1, tc, tc * tc, tc * tc * tc};
        int slot = 1;
        for (int p = 0; p <= 2; ++p)
          for (int r = 0; r <= 2; ++r) {
            if (!p && !r) continue;
            const double f = sp[p] * tp[r] * (p == 2 ? 0.5 : 1) * (r == 2 ? 0.5 : 1), wa = w(sp[3 - p], tp[3 - r]);
            q += f * (wa * v[slot][c] + (1 - wa) * v[slot + 1][c]);
            slot += 2;
          }
      } else {
        const double w10 = w(s, t * t), w01 = w(s * s, t), w11 = w(s, t);
        q += s * (w10 * v[1][c] + (1 - w10) * v[2][c]) + t * (w01 * v[3][c] + (1 - w01) * v[4][c]) +
             s * t * (w11 * v[5][c] + (1 - w11) * v[6][c]);
      }
      const double mu = in.blendShare[i], lambda = sideBlendWeight(s, t, in.parabolic ? 3 : 2);
      out[c] += b * ((1 - mu) * (left + right - q) + mu * (lambda * left + (1 - lambda) * right));
    }
  }
  return out;
}

} // namespace

// ---- domain frames and corner blends ----------------------------------------

/// The regular n-gon's sides for the domain kernels.
ck::DomainSides domainSides(const RegularDomain &domain) {
  ck::DomainSides sides;
  sides.sides = domain.sides();
  for (int i = 0; i < domain.sides(); ++i) {
    const Vec2 p = domain.corner(i), edge = domain.corner(i + 1) - p, axis = edge / dot(edge, edge);
    sides.px[i] = p.x, sides.py[i] = p.y, sides.ex[i] = axis.x, sides.ey[i] = axis.y;
  }
  return sides;
}

/// kCount random points strictly inside `domain`, coordinates into u and v.
void randomInteriorPoints(const RegularDomain &domain, std::mt19937_64 &rng, std::vector<double> &u,
                          std::vector<double> &v) {
  std::uniform_real_distribution<double> unit(-1, 1);
  while (u.size() < kCount) {
    const Vec2 q{unit(rng), unit(rng)};
    bool inside = true;
    for (int i = 0; i < domain.sides() && inside; ++i) inside = domain.perpendicularDistance(i, q.x, q.y).v > 0;
    if (inside) u.push_back(q.x), v.push_back(q.y);
  }
}

TEST(Kernels, DomainFramesAndBlendsAgreeAcrossWidthsAndWithDualArithmetic) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int n = 3; n <= 8; ++n) {
    const RegularDomain domain(n);
    const ck::DomainSides sides = domainSides(domain);
    std::vector<double> u, v;
    randomInteriorPoints(domain, rng, u, v);
    // The independent form: the domain's own frames and cornerProducts in Dual arithmetic.
    for (int exponent : {2, 3}) {
      std::vector<double> frameX(n * kCount), frameY(n * kCount), blend(3 * n * kCount);
      for (size_t k = 0; k < kCount; ++k) {
        std::array<Dual, ck::DomainSides::kMaxSides> powered{}, products{};
        for (int i = 0; i < n; ++i) {
          Dual x, y;
          domain.sideFrame(i, Dual::u(u[k]), Dual::vCoord(v[k]), x, y);
          frameX[i * kCount + k] = x.v, frameY[i * kCount + k] = y.v;
          powered[i] = exponent == 3 ? y * y * y : y * y;
        }
        const Dual total = domain.cornerProducts(powered, products);
        for (int i = 0; i < n; ++i) {
          const Dual b = products[i] / total;
          blend[(3 * i) * kCount + k] = b.v, blend[(3 * i + 1) * kCount + k] = b.du,
                                 blend[(3 * i + 2) * kCount + k] = b.dv;
        }
      }
      for (const auto &w : ck::availableWidths()) {
        SCOPED_TRACE(w.name + ", n = " + std::to_string(n) + ", exponent " + std::to_string(exponent));
        Soa xy(2 * n, kCount), out(3 * n, kCount), values(n, kCount);
        std::array<double *, 8> x{}, y{}, b{}, bu{}, bv{}, alone{};
        for (int i = 0; i < n; ++i)
          x[i] = xy[i], y[i] = xy[n + i], b[i] = out[3 * i], bu[i] = out[3 * i + 1], bv[i] = out[3 * i + 2],
          alone[i] = values[i];
        ck::sideFrames(kCount, sides, u.data(), v.data(), x.data(), y.data(), w.id);
        ck::cornerBlends(kCount, sides, exponent, y.data(), b.data(), bu.data(), bv.data(), w.id);
        ck::cornerBlends(kCount, sides, exponent, y.data(), alone.data(), nullptr, nullptr, w.id);
        std::vector<double> gotX(xy[0], xy[0] + n * kCount), gotY(xy[n], xy[n] + n * kCount);
        EXPECT_LT(relativeDifference(gotX, frameX), 1e-14);
        EXPECT_LT(relativeDifference(gotY, frameY), 1e-14);
        for (int i = 0; i < n; ++i)
          for (int c = 0; c < 3; ++c) {
            const double *expected = blend.data() + (3 * i + c) * kCount;
            EXPECT_LT(relativeDifference({out[3 * i + c], out[3 * i + c] + kCount}, {expected, expected + kCount}), 1e-12)
                << "blend " << i << " component " << c;
          }
        for (int i = 0; i < n; ++i) {
          const double *expected = blend.data() + 3 * i * kCount;
          EXPECT_LT(relativeDifference({values[i], values[i] + kCount}, {expected, expected + kCount}), 1e-13);
        }
      }
    }
  }
}

TEST(Kernels, SweepGradientsAgreeAcrossWidthsAndWithTheDomainsImplicitDerivative) {
  std::mt19937_64 rng(12);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int n = 4; n <= 8; ++n) {
    const RegularDomain domain(n);
    const ck::DomainSides sides = domainSides(domain);
    std::vector<double> u, v;
    randomInteriorPoints(domain, rng, u, v);
    for (int side : {0, n - 1}) {
      std::vector<double> x(kCount), y(kCount), root(kCount), distance(kCount), du(kCount), dv(kCount);
      std::vector<double> expectedU(kCount), expectedV(kCount);
      std::array<double *, 8> xs{}, ys{};
      for (int i = 0; i < n; ++i) xs[i] = i == side ? x.data() : distance.data(), ys[i] = i == side ? y.data() : du.data();
      ck::sideFrames(kCount, sides, u.data(), v.data(), xs.data(), ys.data(), ck::kScalarReference);
      ck::hermiteSweepRoots(kCount, domain.sweepFrame(side), x.data(), y.data(), root.data(), distance.data());
      // The independent form: the domain's implicit differentiation in Dual arithmetic.
      for (size_t k = 0; k < kCount; ++k) {
        const Dual s = domain.hermiteSweepFromRoot(side, Dual::u(u[k]), Dual::vCoord(v[k]), root[k]).s;
        expectedU[k] = s.du, expectedV[k] = s.dv;
      }
      for (const auto &w : ck::availableWidths()) {
        SCOPED_TRACE(w.name + ", n = " + std::to_string(n) + ", side " + std::to_string(side));
        std::fill(du.begin(), du.end(), NAN), std::fill(dv.begin(), dv.end(), NAN);
        ck::hermiteSweepGradients(kCount, domain.sweepFrame(side), sides.ex[side], sides.ey[side], x.data(), y.data(),
                                  root.data(), du.data(), dv.data(), w.id);
        // Relative to the gradient's size: on a square's axis-parallel side one partial is 0.
        std::vector<double> got = du, expected = expectedU;
        got.insert(got.end(), dv.begin(), dv.end()), expected.insert(expected.end(), expectedV.begin(), expectedV.end());
        EXPECT_LT(relativeDifference(got, expected), 1e-12);
      }
    }
  }
}

TEST(Kernels, GregoryPositionsAgreeAcrossWidthsAndWithTheFormula) {
  std::mt19937_64 rng(11);
  for (int kind : {0, 1, 2, 3, 4}) // G¹, G², G² and G¹ with blend shares, G² with shares and saturating reaches
    for (int n : {3, 5, 8}) {
      const bool parabolic = kind == 1 || kind == 2 || kind == 4;
      RandomGregoryInput random(n, parabolic, rng, kind >= 2, kind == 4);
      const ck::GregorySamples &in = random.in;
      const std::vector<ck::GregoryCorner> &corners = random.corners;
      Soa reference(3, kCount);
      double *refOut[3] = {reference[0], reference[1], reference[2]};
      ck::gregoryPositions(kCount, in, corners.data(), refOut, ck::kScalarReference);
      std::vector<double> formula(3 * kCount);
      for (size_t k = 0; k < kCount; ++k) {
        const auto p = gregoryFormula(in, corners.data(), k);
        for (int c = 0; c < 3; ++c) formula[c * kCount + k] = p[c];
      }
      EXPECT_LE(relativeDifference(reference.data, formula), 1e-12) << "n=" << n << " kind " << kind;
      for (const auto &w : ck::availableWidths()) {
        Soa out(3, kCount);
        double *o[3] = {out[0], out[1], out[2]};
        ck::gregoryPositions(kCount, in, corners.data(), o, w.id);
        EXPECT_LE(relativeDifference(out.data, reference.data), 1e-12) << w.name << " n=" << n;
        // Written as points with an offset: the same sums, the offset added last.
        const double offset[3] = {1e3, -2.5, 0.125};
        std::vector<double> points(3 * kCount);
        ck::gregoryPositionsInterleaved(kCount, in, corners.data(), points.data(), offset, w.id);
        std::size_t mismatches = 0;
        for (size_t k = 0; k < kCount; ++k)
          for (int c = 0; c < 3; ++c) mismatches += points[3 * k + c] != out[c][k] + offset[c];
        EXPECT_EQ(mismatches, 0u) << w.name << " n=" << n << " (points)";
      }
    }
}

TEST(Kernels, SaturatedCrossIsReachTimesTanhAndAgreesAcrossWidths) {
  // r tanh(x / r) against std::tanh in long double to a few units in the
  // last place over the arguments a patch meets (sides' parameters and past
  // them), its slope 1 − tanh² to 1e-15, at every width; exact where it
  // must be (0 at 0, r and slope 0 beyond saturation, odd).
  std::vector<double> x;
  for (int k = -4000; k <= 4000; ++k) x.push_back(k / 2000.0);  // [−2, 2], 1/2000 apart
  std::mt19937_64 rng(31);
  std::uniform_real_distribution<double> wide(-3.0, 3.0);
  for (int k = 0; k < 4000; ++k) x.push_back(wide(rng));
  for (double tiny : {1e-300, 1e-20, 1e-9, 4e-5}) x.push_back(tiny), x.push_back(-tiny);
  const std::size_t count = x.size();
  for (double reach : {0.05, 0.1, 0.3, 0.73, 0.999}) {
    std::vector<double> referenceValue(count), referenceSlope(count);
    ck::saturatedCross(count, x.data(), reach, referenceValue.data(), referenceSlope.data(), ck::kScalarReference);
    for (const auto &w : ck::availableWidths()) {
      std::vector<double> value(count), slope(count);
      ck::saturatedCross(count, x.data(), reach, value.data(), slope.data(), w.id);
      for (std::size_t k = 0; k < count; ++k) {
        // Targets without fused multiply-adds round differently: units in the last place apart.
        ASSERT_NEAR(value[k], referenceValue[k], 4 * 2.220446049250313e-16 * std::abs(referenceValue[k]))
            << w.name << " reach " << reach << " x " << x[k];
        ASSERT_NEAR(slope[k], referenceSlope[k], 1e-15) << w.name << " reach " << reach << " x " << x[k];
        const long double th = std::tanh(static_cast<long double>(x[k] * (1.0 / reach)));
        const double expected = static_cast<double>(reach * th);
        ASSERT_NEAR(value[k], expected, 4 * 2.220446049250313e-16 * std::abs(expected))
            << w.name << " reach " << reach << " x " << x[k];
        ASSERT_NEAR(slope[k], static_cast<double>(1 - th * th), 1e-15) << w.name << " reach " << reach << " x " << x[k];
      }
    }
    const double special[] = {0.0, 25 * reach, -25 * reach, 1e3, NAN};
    double value[5], slope[5];
    ck::saturatedCross(5, special, reach, value, slope);
    EXPECT_EQ(value[0], 0.0);
    EXPECT_EQ(slope[0], 1.0);
    EXPECT_EQ(value[1], reach);
    EXPECT_EQ(value[2], -reach);
    EXPECT_EQ(slope[1], 0.0);
    EXPECT_EQ(value[3], reach);
    EXPECT_TRUE(std::isnan(value[4]));
  }
}

TEST(Kernels, SharedG2CornerWeightsGiveTheSamePositions) {
  // gregoryCornerWeights against the weights' definition (plain divisions in
  // long double, 0 at the corner itself), across widths; gregoryPositions
  // given them writes the very numbers it computes without them.
  std::mt19937_64 rng(23);
  for (int n : {3, 5, 8}) {
    RandomGregoryInput random(n, true, rng);
    ck::GregorySamples &in = random.in;
    Soa &s = random.s;
    const std::vector<ck::GregoryCorner> &corners = random.corners;
    for (const auto &w : ck::availableWidths()) {
      Soa weights(8 * n, kCount);
      for (int i = 0; i < n; ++i) {
        double *into[8];
        for (int j = 0; j < 8; ++j) into[j] = weights[8 * i + j];
        ck::gregoryCornerWeights(kCount, s[i], s[(i + n - 1) % n], into[0], kCount, w.id);
        for (size_t k = 0; k < kCount; ++k) {
          const long double si = s[i][k], ti = 1 - static_cast<long double>(s[(i + n - 1) % n][k]);
          int j = 0;
          for (int p = 0; p <= 2; ++p)
            for (int q = 0; q <= 2; ++q) {
              if (!p && !q) continue;
              const long double den = std::pow(si, 3 - p) + std::pow(ti, 3 - q);
              const long double expected = den == 0 ? 0 : si * si * si * std::pow(ti, q) / den;
              ASSERT_NEAR(into[j][k], static_cast<double>(expected), 1e-14 * (1 + std::abs(static_cast<double>(expected))))
                  << w.name << " n=" << n << " corner " << i << " weight " << j << " sample " << k;
              ++j;
            }
        }
        in.weights[i] = weights[8 * i];
      }
      in.weightStride = kCount;
      Soa shared(3, kCount), computed(3, kCount);
      double *o[3] = {shared[0], shared[1], shared[2]}, *c[3] = {computed[0], computed[1], computed[2]};
      ck::gregoryPositions(kCount, in, corners.data(), o, w.id);
      for (int i = 0; i < n; ++i) in.weights[i] = nullptr;
      ck::gregoryPositions(kCount, in, corners.data(), c, w.id);
      std::size_t mismatches = 0;
      for (size_t k = 0; k < 3 * kCount; ++k) mismatches += shared.data[k] != computed.data[k];
      EXPECT_EQ(mismatches, 0u) << w.name << " n=" << n;
      // A corner whose ribbons saturate takes the weights of its saturated
      // parameters, not the given ones (those of the sweep's own): here
      // corners 0 and 1 (ribbon 0 saturates), the others unsaturated.
      ck::GregorySamples saturated = in;
      for (int i = 0; i < n; ++i) saturated.weights[i] = weights[8 * i], saturated.reach[i] = i == 0 ? 0.05 : 1.0;
      Soa given(3, kCount), own(3, kCount);
      double *g[3] = {given[0], given[1], given[2]}, *h[3] = {own[0], own[1], own[2]};
      ck::gregoryPositions(kCount, saturated, corners.data(), g, w.id);
      for (int i = 0; i < n; ++i) saturated.weights[i] = nullptr;
      ck::gregoryPositions(kCount, saturated, corners.data(), h, w.id);
      mismatches = 0;
      for (size_t k = 0; k < 3 * kCount; ++k) mismatches += given.data[k] != own.data[k];
      EXPECT_EQ(mismatches, 0u) << w.name << " n=" << n << " (saturated corners)";
      EXPECT_GT(relativeDifference(own.data, computed.data), 1e-6) << "the reaches saturate";
    }
  }
}

TEST(Kernels, TableEvaluationAgreesAcrossWidthsAndWithHorner) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2, 2), unit(0, 1);
  // {coordinates, row width}: 6 in rows of 8 and 9 as rows of 8 and a tail
  // of one, the engine's tables (kernels specialized for them); the others
  // through the general path: partial rows, tails of one to three, tail only.
  const std::pair<int, int> layouts[] = {{6, 8}, {9, 8}, {3, 4}, {5, 8}, {5, 4}, {9, 12}, {7, 4}, {1, 0}};
  for (const auto &layout : layouts) {
    const int dims = layout.first, padded = layout.second; // named: lambdas below capture them
    const int rowDims = std::min(dims, padded);
    const size_t block = 6 * padded + 8 * (dims - rowDims);
    // Coefficient of t^r, coordinate d, interval j (kernels::PolynomialTable).
    auto at = [&](size_t j, int r, int d) {
      return j * block + (d < rowDims ? r * padded + d : 6 * padded + 8 * (d - rowDims) + r);
    };
    // Uneven intervals over [0, 1], a coarse grid: the forward search moves.
    std::vector<double> edges{0};
    while (edges.back() < 1) edges.push_back(std::min(1.0, edges.back() + 0.002 + 0.05 * unit(rng)));
    const size_t m = edges.size() - 1;
    std::vector<double> starts(edges.begin(), edges.end() - 1), ends(edges.begin() + 1, edges.end()), inverse(m);
    for (size_t j = 0; j < m; ++j) inverse[j] = 1 / (ends[j] - starts[j]);
    std::vector<double> coefficients(m * block, 0.0);
    for (size_t j = 0; j < m; ++j)
      for (int r = 0; r < 6; ++r)
        for (int d = 0; d < dims; ++d) coefficients[at(j, r, d)] = u(rng);
    // A coarse grid (several forward steps) and a fine one (at most one:
    // the cells carry their first interval's end).
    for (const size_t cells : {size_t{64}, size_t{2048}}) {
      std::vector<std::uint32_t> first(cells);
      std::vector<double> firstEnd(cells);
      int steps = 0;
      for (size_t c = 0, j = 0; c < cells; ++c) {
        while (j + 1 < m && ends[j] < double(c) / cells) ++j;
        first[c] = static_cast<std::uint32_t>(j);
        firstEnd[c] = j + 1 < m ? ends[j] : INFINITY;
        size_t last = j;
        while (last + 1 < m && ends[last] < double(c + 1) / cells) ++last;
        steps = std::max(steps, int(last - j));
      }
      ASSERT_EQ(steps > 1, cells == 64);
      ck::PolynomialTable table;
      table.dims = dims, table.paddedDims = padded, table.steps = steps, table.intervals = m, table.cells = cells;
      table.starts = starts.data(), table.ends = ends.data(), table.inverseWidths = inverse.data();
      table.coefficients = coefficients.data(), table.cellFirst = first.data();
      if (steps <= 1) table.cellFirstEnd = firstEnd.data();
      std::vector<double> s(kCount);
      for (double &x : s) x = unit(rng);
      // From the middle on, runs of eight as a tessellation's rows give
      // them: inside one interval (the kernels' broadcast path), across an
      // interval's end, rising or falling over a few intervals (the
      // windowed lookups), up to s = 1 (the window at the table's end), and
      // out of [0, 1] at either end (the windows refused).
      for (size_t run = kCount / 16; 8 * run + 8 <= kCount; ++run) {
        const size_t j = run % (m - 1);
        double *runStart = &s[8 * run];
        switch (run % 6) {
        case 0:
        case 1: {
          const double from = run % 6 ? 0.5 * (starts[j] + ends[j]) : starts[j], to = run % 6 ? ends[j + 1] : ends[j];
          for (size_t q = 0; q < 8; ++q) runStart[q] = from + (to - from) * (0.05 + 0.9 * unit(rng));
          break;
        }
        case 2:
        case 3: { // sorted, rising or falling, over about four intervals
          const double from = starts[j], to = ends[std::min(m - 1, j + 3)];
          for (size_t q = 0; q < 8; ++q) runStart[q] = from + (to - from) * unit(rng);
          std::sort(runStart, runStart + 8);
          if (run % 6 == 3) std::reverse(runStart, runStart + 8);
          if (run % 12 == 3) runStart[4] = ends[j]; // on an interval's end: the interval to its left
          break;
        }
        case 4: // the last intervals, up to s = 1
          for (size_t q = 0; q < 8; ++q) runStart[q] = 1 - 0.02 * (7 - q) / 7.0;
          break;
        default: // out of [0, 1]
          for (size_t q = 0; q < 8; ++q) runStart[q] = run % 12 == 5 ? -0.001 * q : 1 + 0.001 * q;
          break;
        }
      }
      s[0] = 0, s[1] = 1, s[2] = edges[3]; // the ends, and a break (the interval to its left)
      std::vector<double> horner(dims * kCount), hornerSlope(dims * kCount);
      for (size_t k = 0; k < kCount; ++k) {
        size_t j = 0;
        while (j + 1 < m && ends[j] < s[k]) ++j;
        const double t = (s[k] - starts[j]) * inverse[j];
        for (int d = 0; d < dims; ++d) {
          double v = 0, dv = 0;
          for (int r = 5; r >= 0; --r) v = v * t + coefficients[at(j, r, d)];
          for (int r = 1; r <= 5; ++r) dv += r * coefficients[at(j, r, d)] * std::pow(t, r - 1);
          horner[d * kCount + k] = v, hornerSlope[d * kCount + k] = dv * inverse[j];
        }
      }
      for (const auto &w : ck::availableWidths()) {
        Soa values(dims, kCount), slopes(dims, kCount);
        std::vector<double *> v(dims), sl(dims);
        for (int d = 0; d < dims; ++d) v[d] = values[d], sl[d] = slopes[d];
        ck::evaluateTable(kCount, table, s.data(), v.data(), sl.data(), w.id);
        EXPECT_LE(relativeDifference(values.data, horner), 1e-12) << w.name << " dims " << dims << " in rows of " << padded << ", cells " << cells;
        EXPECT_LE(relativeDifference(slopes.data, hornerSlope), 1e-12) << w.name << " dims " << dims << " in rows of " << padded << ", cells " << cells;
        // Values alone (the position path): the same values.
        Soa alone(dims, kCount);
        for (int d = 0; d < dims; ++d) v[d] = alone[d];
        ck::evaluateTable(kCount, table, s.data(), v.data(), nullptr, w.id);
        EXPECT_EQ(alone.data, values.data) << w.name << " dims " << dims << " in rows of " << padded << ", cells " << cells << " (values alone)";
        // The tail coefficients also interval after interval (the eight-lane
        // path permutes them out of a window of intervals): the same bits.
        std::vector<double> tailByInterval;
        for (int e = 0; e < dims - rowDims; ++e)
          for (int r = 0; r < 6; ++r)
            for (size_t j = 0; j < m; ++j) tailByInterval.push_back(coefficients[at(j, r, rowDims + e)]);
        if (!tailByInterval.empty()) {
          ck::PolynomialTable permuted = table;
          permuted.tailByInterval = tailByInterval.data();
          Soa other(dims, kCount), otherSlopes(dims, kCount);
          for (int d = 0; d < dims; ++d) v[d] = other[d], sl[d] = otherSlopes[d];
          ck::evaluateTable(kCount, permuted, s.data(), v.data(), sl.data(), w.id);
          EXPECT_EQ(other.data, values.data) << w.name << " dims " << dims << " (tail by interval)";
          EXPECT_EQ(otherSlopes.data, slopes.data) << w.name << " dims " << dims << " (tail by interval)";
          for (int d = 0; d < dims; ++d) v[d] = other[d];
          ck::evaluateTable(kCount, permuted, s.data(), v.data(), nullptr, w.id);
          EXPECT_EQ(other.data, values.data) << w.name << " dims " << dims << " (tail by interval, values alone)";
        }
        // The AVX-512 eight-lane path and the four-lane one: the same bits,
        // whichever this CPU takes by default (eightLaneTables).
        for (const bool eight : {false, true}) {
          ck::setEightLaneTables(eight);
          Soa other(dims, kCount), otherSlopes(dims, kCount);
          for (int d = 0; d < dims; ++d) v[d] = other[d], sl[d] = otherSlopes[d];
          ck::evaluateTable(kCount, table, s.data(), v.data(), sl.data(), w.id);
          EXPECT_EQ(other.data, values.data) << w.name << (eight ? " eight" : " four") << " lanes, dims " << dims;
          EXPECT_EQ(otherSlopes.data, slopes.data) << w.name << (eight ? " eight" : " four") << " lanes, dims " << dims;
        }
        ck::setEightLaneTables(std::nullopt);
      }
    }
  }
}

namespace {

/// Points of side 0's frame that the fast sweep solver must hand to the
/// robust one or get right anyway: on the three sides the sweep touches, at
/// and near every corner, near the radial apex, outside the domain, and
/// across the whole domain.
std::vector<Vec2> hardSweepPoints(int n, const SideFrame &side, std::mt19937_64 &rng) {
  const RegularDomain domain(n);
  auto toFrame = [&](const Vec2 &q) {
    const Vec2 r = q - side.p0;
    return Vec2{dot(r, side.e) / dot(side.e, side.e), cross(side.e, r) / dot(side.e, side.e)};
  };
  std::uniform_real_distribution<double> unit(0, 1), box(-1.2, 1.2), angle(0, 2 * std::numbers::pi);
  std::vector<Vec2> points;
  const ck::SweepFrame &f = side.frame;
  for (int k = 0; k < 2000; ++k) {
    const double t = unit(rng);
    points.push_back({t, 0});                           // side 0
    points.push_back({t * f.ax, t * f.ay});             // side −1, leaving (0, 0) along a
    points.push_back({1 + t * f.bx, t * f.by});         // side +1, leaving (1, 0) along b
    points.push_back(toFrame(Vec2{box(rng), box(rng)})); // anywhere, mostly outside
  }
  std::vector<Vec2> specials;
  for (int i = 0; i < n; ++i) specials.push_back(toFrame(domain.corner(i)));
  specials.push_back(toFrame(Vec2{0, 0})); // the domain's centre
  if (!f.parallel) specials.push_back({f.apexX, f.apexY});
  for (const Vec2 &c : specials) {
    points.push_back(c);
    for (double r = 1e-15; r < 0.1; r *= 3.7)
      for (int k = 0; k < 8; ++k) {
        const double phi = angle(rng);
        points.push_back(c + Vec2{std::cos(phi), std::sin(phi)} * r);
      }
  }
  while (points.size() < 30000) {
    const Vec2 q{box(rng), box(rng)};
    bool inside = true;
    for (int i = 0; i < n && inside; ++i) inside = domain.perpendicularDistance(i, q.x, q.y).v > 0;
    if (inside) points.push_back(toFrame(q));
  }
  return points;
}

TEST(Kernels, CompositeRibbonAgreesAcrossWidthsAndWithDualArithmetic) {
  // Reference: the CR formula ([VSR]: three ribbons per side, Coons
  // blending, two Gregory corrections) in Dual arithmetic with the engine's
  // scalar gregoryCorrection. Some samples sit at a side's start corner
  // (s = d = 0, where W takes (a + b) / 2) and some have a zero blend (the
  // side is skipped).
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> unit(0.02, 0.98), u(-2, 2);
  for (int n : {3, 5, 8}) {
    constexpr size_t count = 203;
    Soa s(3 * n, count), dist(3 * n, count), blend(3 * n, count), ribbons(36 * n, count, &rng);
    for (size_t a = 0; a < size_t(3 * n); ++a)
      for (size_t k = 0; k < count; ++k) {
        s[a][k] = a % 3 ? u(rng) : unit(rng), dist[a][k] = a % 3 ? u(rng) : unit(rng);
        blend[a][k] = a % 3 ? u(rng) : unit(rng);
      }
    for (int i = 0; i < n; ++i) {
      s[3 * i][7 * i] = dist[3 * i][7 * i] = 0;                         // at the start corner
      for (int part = 0; part < 3; ++part) blend[3 * i + part][7 * i + 3] = 0; // skipped
    }
    ck::CompositeSamples in;
    in.sides = n;
    for (int i = 0; i < n; ++i) {
      for (int part = 0; part < 3; ++part)
        in.s[i][part] = s[3 * i + part], in.d[i][part] = dist[3 * i + part], in.blend[i][part] = blend[3 * i + part];
      for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c) {
          const size_t base = 36 * i + 12 * r;
          in.P[i][r][c] = ribbons[base + c], in.T[i][r][c] = ribbons[base + 3 + c];
          in.dP[i][r][c] = ribbons[base + 6 + c], in.dT[i][r][c] = ribbons[base + 9 + c];
        }
    }
    std::vector<ck::GregoryCorner> left(n), right(n);
    for (auto *corners : {&left, &right})
      for (auto &corner : *corners)
        for (auto &v : corner.v)
          for (double &x : v) x = u(rng);
    auto cornerData = [](const ck::GregoryCorner &corner) {
      const auto &v = corner.v;
      auto vec = [](const double *p) { return Vec3{p[0], p[1], p[2]}; };
      return CornerData{vec(v[0]), vec(v[1]), vec(v[3]), vec(v[5]), vec(v[2]), vec(v[4]), vec(v[6])};
    };
    std::vector<double> formula(9 * count);
    for (size_t k = 0; k < count; ++k) {
      auto at = [&](const double *const(&a)[3]) { return Vec3{a[0][k], a[1][k], a[2][k]}; };
      auto gamma = [](Dual x) { return x / (x * 2.0 + 1.0); };
      auto hermite0 = [](Dual x) { return x * x * (x * 2.0 - 3.0) + 1.0; };
      DualVec3 sum{};
      for (int i = 0; i < n; ++i) {
        const Dual si{s[3 * i][k], s[3 * i + 1][k], s[3 * i + 2][k]};
        const Dual di{dist[3 * i][k], dist[3 * i + 1][k], dist[3 * i + 2][k]};
        const Dual b{blend[3 * i][k], blend[3 * i + 1][k], blend[3 * i + 2][k]};
        if (b.isZero()) continue;
        const Dual one = 1.0, sigma = one - si;
        auto ribbon = [&](int r, Dual side, Dual distance) {
          return DualVec3::along(at(in.P[i][r]), at(in.dP[i][r]), side) +
                 gamma(distance) * DualVec3::along(at(in.T[i][r]), at(in.dT[i][r]), side);
        };
        const DualVec3 centre = ribbon(0, si, di), leftRibbon = ribbon(1, one - di, si),
                       rightRibbon = ribbon(2, di, sigma);
        const DualVec3 leftCorrection = gregoryCorrection(cornerData(left[i]), si, di, gamma(si), gamma(di));
        const DualVec3 rightCorrection =
            gregoryCorrection(cornerData(right[i]), sigma, di, gamma(sigma), gamma(di));
        const Dual a0s = hermite0(si), a1s = one - a0s, a0d = hermite0(di);
        sum += b * (a0s * leftRibbon + a0d * centre + a1s * rightRibbon - (a0s * a0d) * leftCorrection -
                    (a1s * a0d) * rightCorrection);
      }
      sum = Dual(0.5) * sum;
      const Vec3 parts[3] = {sum.v, sum.du, sum.dv};
      for (int p = 0; p < 3; ++p)
        for (int c = 0; c < 3; ++c) formula[(3 * p + c) * count + k] = parts[p][c];
    }
    const std::vector<double> positions(formula.begin(), formula.begin() + 3 * count);
    for (const auto &w : ck::availableWidths()) {
      Soa jets(9, count), points(3, count);
      ck::compositeRibbonJets(count, in, left.data(), right.data(), span9(jets), w.id);
      EXPECT_LE(relativeDifference(jets.data, formula), 1e-12) << w.name << " n=" << n;
      double *const out[3] = {points[0], points[1], points[2]};
      ck::compositeRibbonPositions(count, in, left.data(), right.data(), out, w.id);
      EXPECT_LE(relativeDifference(points.data, positions), 1e-12) << w.name << " n=" << n;
    }
  }
}

TEST(Kernels, SweepFastPathAgreesWithRobustSolverWhereItFallsBack) {
  std::mt19937_64 rng(17);
  for (int n = 3; n <= 8; ++n) {
    const SideFrame side = sideZeroFrame(n);
    const std::vector<Vec2> points = hardSweepPoints(n, side, rng);
    const size_t count = points.size();
    std::vector<double> x(count), y(count);
    for (size_t k = 0; k < count; ++k) x[k] = points[k].x, y[k] = points[k].y;
    std::vector<double> sRobust(count), dRobust(count);
    ck::hermiteSweepRootsRobust(count, side.frame, x.data(), y.data(), sRobust.data(), dRobust.data(),
                                ck::kScalarReference);
    for (const auto &w : ck::availableWidths()) {
      std::vector<double> s(count), d(count), sr(count), dr(count);
      const size_t fallbacks = ck::hermiteSweepRoots(count, side.frame, x.data(), y.data(), s.data(), d.data(), w.id);
      ck::hermiteSweepRootsRobust(count, side.frame, x.data(), y.data(), sr.data(), dr.data(), w.id);
      // The robust solver is width-independent, and the fast one agrees with it.
      EXPECT_LE(relativeDifference(sr, sRobust), 1e-12) << w.name << " n=" << n;
      size_t mismatches = 0;
      for (size_t k = 0; k < count; ++k)
        if (!(std::abs(s[k] - sRobust[k]) <= 1e-12 && std::abs(d[k] - dRobust[k]) <= 1e-12 * (1 + std::abs(dRobust[k]))))
          if (++mismatches <= 5)
            ADD_FAILURE() << w.name << " n=" << n << " at (" << x[k] << ", " << y[k] << "): s " << s[k] << " vs "
                          << sRobust[k] << ", d " << d[k] << " vs " << dRobust[k];
      EXPECT_EQ(mismatches, 0u) << w.name << " n=" << n;
      // These points exercise the fallback: at least every point on the
      // neighbouring sides (a root at an end of [0, 1]) and every corner.
      EXPECT_GE(fallbacks, 4000u) << w.name << " n=" << n;
      EXPECT_LT(fallbacks, count) << w.name << " n=" << n;
    }
  }
}

TEST(Kernels, SweepFastPathServesAlmostAllDomainPoints) {
  // Inside a regular domain with n ≥ 4 the sweeplines of a side do not cross,
  // so the root is unique and the fast path should certify nearly every
  // point. n = 3 loses about 6 %: near the fold at the opposite corner
  // several roots lie on [0, 1], or the quotient comes too close to zero.
  std::mt19937_64 rng(23);
  for (int n = 3; n <= 8; ++n) {
    const RegularDomain domain(n);
    std::vector<double> x, y;
    randomInteriorPoints(n, 50000, rng, x, y);
    const SideFrame side = sideZeroFrame(n);
    std::vector<double> s(x.size()), d(x.size());
    const size_t fallbacks = ck::hermiteSweepRoots(x.size(), side.frame, x.data(), y.data(), s.data(), d.data());
    const double share = double(fallbacks) / double(x.size());
    std::printf("n=%d: %.4f%% of domain points took the robust solver\n", n, 100 * share);
    EXPECT_LT(share, n == 3 ? 0.08 : 0.002) << "n=" << n;
  }
}

} // namespace

TEST(Kernels, GregoryJetsAgreeAcrossWidthsAndWithDualArithmetic) {
  // Reference: the engine's scalar correction patches (patch.hpp) and ribbon
  // formula in Dual arithmetic, whose product and quotient rules are
  // independent of the kernel's hand-derived derivatives.
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> unit(0.02, 0.98), u(-2, 2);
  // G¹, G², G² and G¹ with blend shares 1, 0 and random ones, G² with shares
  // and saturating reaches.
  for (int kind : {0, 1, 2, 3, 4})
    for (int n : {3, 5, 8}) {
      const bool parabolic = kind == 1 || kind == 2 || kind == 4;
      constexpr size_t count = 203;
      Soa s(3 * n, count), blend(3 * n, count), jets(18 * n, count, &rng);
      for (size_t a = 0; a < size_t(3 * n); ++a)
        for (size_t k = 0; k < count; ++k) s[a][k] = a % 3 ? u(rng) : unit(rng), blend[a][k] = a % 3 ? u(rng) : unit(rng);
      ck::GregoryJetSamples in;
      in.values.sides = n, in.values.parabolic = parabolic;
      for (int i = 0; i < n; ++i) {
        in.values.s[i] = s[3 * i], in.sDu[i] = s[3 * i + 1], in.sDv[i] = s[3 * i + 2];
        in.values.blend[i] = blend[3 * i], in.blendDu[i] = blend[3 * i + 1], in.blendDv[i] = blend[3 * i + 2];
        for (int c = 0; c < 3; ++c) {
          in.values.P[i][c] = jets[18 * i + c], in.values.T[i][c] = jets[18 * i + 3 + c], in.values.C[i][c] = jets[18 * i + 6 + c];
          in.dP[i][c] = jets[18 * i + 9 + c], in.dT[i][c] = jets[18 * i + 12 + c], in.dC[i][c] = jets[18 * i + 15 + c];
        }
      }
      std::vector<ck::GregoryCorner> corners(n);
      for (auto &corner : corners)
        for (auto &v : corner.v)
          for (double &x : v) x = u(rng);
      if (kind >= 2)
        for (int i = 0; i < n; ++i) in.values.blendShare[i] = i == 0 ? 1.0 : i == 1 ? 0.0 : unit(rng);
      if (kind == 4) RandomGregoryInput::saturatingReaches(n, rng, in.values.reach);
      // r tanh(d / r) in Dual arithmetic: the chain rule of Dual::apply.
      auto saturate = [&](Dual d, double reach) {
        if (reach >= 1) return d;
        const double th = std::tanh(d.v / reach);
        return d.apply(reach * th, 1 - th * th);
      };
      auto vec = [](const double *p) { return Vec3{p[0], p[1], p[2]}; };
      std::vector<double> formula(9 * count);
      for (size_t k = 0; k < count; ++k) {
        auto at = [&](const double *const(&a)[3]) { return Vec3{a[0][k], a[1][k], a[2][k]}; };
        DualVec3 sum{};
        for (int i = 0; i < n; ++i) {
          const int prev = (i + n - 1) % n;
          const Dual si{s[3 * i][k], s[3 * i + 1][k], s[3 * i + 2][k]}, sp{s[3 * prev][k], s[3 * prev + 1][k], s[3 * prev + 2][k]};
          const Dual t = Dual(1.0) - sp, b{blend[3 * i][k], blend[3 * i + 1][k], blend[3 * i + 2][k]};
          auto ribbon = [&](int side, Dual sigma, Dual delta) {
            DualVec3 r = DualVec3::along(at(in.values.P[side]), at(in.dP[side]), sigma) +
                         delta * DualVec3::along(at(in.values.T[side]), at(in.dT[side]), sigma);
            if (parabolic) r += (Dual(0.5) * delta * delta) * DualVec3::along(at(in.values.C[side]), at(in.dC[side]), sigma);
            return r;
          };
          const auto &v = corners[i].v;
          const Dual sc = saturate(si, in.values.reach[prev]), tc = saturate(t, in.values.reach[i]);
          DualVec3 q;
          if (parabolic) {
            CornerData2 c{};
            c.a[0][0] = vec(v[0]);
            int slot = 1;
            for (int p = 0; p <= 2; ++p)
              for (int r = 0; r <= 2; ++r)
                if (p || r) c.a[p][r] = vec(v[slot]), c.b[p][r] = vec(v[slot + 1]), slot += 2;
            q = gregoryCorrection2(c, sc, tc);
          } else {
            const CornerData c{vec(v[0]), vec(v[1]), vec(v[3]), vec(v[5]), vec(v[2]), vec(v[4]), vec(v[6])};
            q = gregoryCorrection(c, si, t, si, t);
          }
          const DualVec3 left = ribbon(prev, sp, sc), right = ribbon(i, si, tc);
          const double mu = in.values.blendShare[i];
          const Dual sm = parabolic ? si * si * si : si * si, tm = parabolic ? t * t * t : t * t;
          const Dual lambda = tm / (sm + tm);
          sum += b * (Dual(1 - mu) * (left + right - q) + Dual(mu) * (lambda * left + (Dual(1.0) - lambda) * right));
        }
        const Vec3 parts[3] = {sum.v, sum.du, sum.dv};
        for (int p = 0; p < 3; ++p)
          for (int c = 0; c < 3; ++c) formula[(3 * p + c) * count + k] = parts[p][c];
      }
      for (const auto &w : ck::availableWidths()) {
        Soa out(9, count);
        ck::gregoryJets(count, in, corners.data(), span9(out), w.id);
        EXPECT_LE(relativeDifference(out.data, formula), 1e-12) << w.name << " n=" << n << " kind " << kind;
      }
      // The gradients given in frames turned by a random angle per side and
      // per corner, the turns given with them (as a plan's arrays come): the
      // same jets. Turned by θ, (g₁, g₂) = (c ∂u + s ∂v, −s ∂u + c ∂v).
      std::uniform_real_distribution<double> angle(-3.2, 3.2);
      Soa turned(4 * n, count);
      ck::GregoryJetSamples inTurned = in;
      for (int i = 0; i < n; ++i)
        for (int which = 0; which < 2; ++which) {
          const double theta = angle(rng), c = std::cos(theta), t = std::sin(theta);
          const double *du = which ? in.blendDu[i] : in.sDu[i], *dv = which ? in.blendDv[i] : in.sDv[i];
          double *g1 = turned[4 * i + 2 * which], *g2 = turned[4 * i + 2 * which + 1];
          for (size_t k = 0; k < count; ++k) g1[k] = c * du[k] + t * dv[k], g2[k] = -t * du[k] + c * dv[k];
          double(&turn)[2] = which ? inTurned.blendTurn[i] : inTurned.sideTurn[i];
          turn[0] = c, turn[1] = t;
          (which ? inTurned.blendDu[i] : inTurned.sDu[i]) = g1;
          (which ? inTurned.blendDv[i] : inTurned.sDv[i]) = g2;
        }
      for (const auto &w : ck::availableWidths()) {
        Soa out(9, count);
        ck::gregoryJets(count, inTurned, corners.data(), span9(out), w.id);
        EXPECT_LE(relativeDifference(out.data, formula), 1e-12) << w.name << " n=" << n << " kind " << kind << " (turned gradients)";
      }
      if (!parabolic) continue;
      // G²: given the corners' weights and partials from
      // gregoryCornerWeightJets, the very numbers it computes without them
      // (kind 4: corners whose cross parameters saturate compute their own);
      // the weights' partials against central differences of the weights.
      for (const auto &w : ck::availableWidths()) {
        Soa weights(24 * n, count), computed(9, count), shared(9, count);
        ck::GregoryJetSamples withWeights = in;
        for (int i = 0; i < n; ++i) {
          ck::gregoryCornerWeightJets(count, s[3 * i], s[3 * ((i + n - 1) % n)], weights[24 * i], count, w.id);
          withWeights.weightJets[i] = weights[24 * i];
        }
        withWeights.weightJetStride = count;
        ck::gregoryJets(count, in, corners.data(), span9(computed), w.id);
        ck::gregoryJets(count, withWeights, corners.data(), span9(shared), w.id);
        std::size_t mismatches = 0;
        for (std::size_t a = 0; a < computed.data.size(); ++a) mismatches += computed.data[a] != shared.data[a];
        EXPECT_EQ(mismatches, 0u) << w.name << " n=" << n << " kind " << kind << " (shared weights)";
        const double h = 1e-6;
        for (std::size_t k = 0; k < count; k += 17) {
          const double si = s[0][k], sp = s[3 * (n - 1)][k];
          double at[4][24];
          const double sArg[4] = {si + h, si - h, si, si}, spArg[4] = {sp, sp, sp - h, sp + h}; // t = 1 − sp: ±h
          for (int e = 0; e < 4; ++e) ck::gregoryCornerWeightJets(1, &sArg[e], &spArg[e], at[e], 1, w.id);
          for (int j = 0; j < 8; ++j) {
            EXPECT_NEAR(weights[8 + j][k], (at[0][j] - at[1][j]) / (2 * h), 1e-6) << w.name << " weight " << j << " d/ds";
            EXPECT_NEAR(weights[16 + j][k], (at[2][j] - at[3][j]) / (2 * h), 1e-6) << w.name << " weight " << j << " d/dt";
          }
        }
      }
    }
}

TEST(Kernels, JetVerticesAreOffsetPointsAndUnitNormalsAtEveryWidth) {
  // Random jets, with some rows made degenerate (dv parallel to du, or
  // both zero) and one non-finite, at a count that leaves a tail.
  std::mt19937_64 rng(41);
  const size_t count = 1003;
  Soa jets(9, count, &rng);
  for (size_t k = 0; k < count; k += 97)
    for (int c = 0; c < 3; ++c) jets[6 + c][k] = 2.5 * jets[3 + c][k]; // parallel
  for (int c = 3; c < 9; ++c) jets[c][500] = 0;                          // both zero
  jets[3][700] = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::uint32_t> expectedIndices;
  for (size_t k = 0; k < count; ++k) {
    const Vec3 du{jets[3][k], jets[4][k], jets[5][k]}, dv{jets[6][k], jets[7][k], jets[8][k]};
    if (squaredNorm(cross(du, dv)) <= 1e-24 * squaredNorm(du) * squaredNorm(dv))
      expectedIndices.push_back(static_cast<std::uint32_t>(k));
  }
  const size_t expectedDegenerate = expectedIndices.size();
  ASSERT_GE(expectedDegenerate, count / 97);
  const double *const columns[9] = {jets[0], jets[1], jets[2], jets[3], jets[4], jets[5], jets[6], jets[7], jets[8]};
  const double offset[3] = {1.5, -2.25, 1e3};
  for (const auto &w : ck::availableWidths()) {
    std::vector<Vec3> points(count), normals(count);
    std::vector<std::uint32_t> flat(count);
    const size_t degenerate = ck::jetVertices(count, columns, offset, &points[0].x, &normals[0].x, flat.data(), w.id);
    EXPECT_EQ(degenerate, expectedDegenerate) << w.name;
    // Their indices, in order: exactly the degenerate jets.
    flat.resize(degenerate);
    EXPECT_EQ(flat, expectedIndices) << w.name;
    for (size_t k = 0; k < count; ++k) {
      // The points exactly: one addition each.
      ASSERT_EQ(points[k].x, jets[0][k] + offset[0]) << w.name << " " << k;
      ASSERT_EQ(points[k].y, jets[1][k] + offset[1]) << w.name << " " << k;
      ASSERT_EQ(points[k].z, jets[2][k] + offset[2]) << w.name << " " << k;
      const Vec3 du{jets[3][k], jets[4][k], jets[5][k]}, dv{jets[6][k], jets[7][k], jets[8][k]};
      const Vec3 expected = normalized(cross(du, dv));
      // A degenerate jet's cross product is rounding noise (the caller
      // replaces its normal): only its length is checked.
      if (squaredNorm(cross(du, dv)) <= 1e-24 * squaredNorm(du) * squaredNorm(dv)) {
        if (norm(expected) > 0) {
          ASSERT_NEAR(norm(normals[k]), 1.0, 4e-16) << w.name << " " << k;
        }
        continue;
      }
      if (!isFinite(expected) || norm(expected) == 0) {
        // normalized()'s zero vector where the length is not above zero;
        // NaN where a component is.
        if (norm(expected) == 0) {
          ASSERT_EQ(norm(normals[k]), 0.0) << w.name << " " << k;
        }
        continue;
      }
      // Unit, and the direction of du × dv, to the rounding of one product
      // more than normalized()'s quotients.
      ASSERT_NEAR(norm(normals[k]), 1.0, 4e-16) << w.name << " " << k;
      ASSERT_LE(norm(normals[k] - expected), 8e-16) << w.name << " " << k;
    }
  }
}

TEST(Kernels, RowTrianglesAreTheZipOrderAtEveryWidth) {
  std::mt19937 rng(11);
  // Every row length up to a few vectors of any width, ids at random: each
  // triangle checked against the order the header gives, written out here
  // triangle by triangle.
  for (size_t m = 1; m <= 70; ++m) {
    std::vector<std::uint32_t> lower(m + 1), upper(m);
    for (auto &id : lower) id = static_cast<std::uint32_t>(rng());
    for (auto &id : upper) id = static_cast<std::uint32_t>(rng());
    std::vector<std::array<std::uint32_t, 3>> expected;
    if (m == 1) {
      expected.push_back({lower[0], lower[1], upper[0]});
    } else {
      for (size_t j = 0; j + 2 < m; ++j) {
        expected.push_back({lower[j], lower[j + 1], upper[j]});
        expected.push_back({lower[j + 1], upper[j + 1], upper[j]});
      }
      expected.push_back({lower[m - 2], lower[m - 1], upper[m - 2]});
      expected.push_back({lower[m - 1], lower[m], upper[m - 2]});
      expected.push_back({lower[m], upper[m - 1], upper[m - 2]});
    }
    ASSERT_EQ(expected.size(), 2 * m - 1);
    for (const auto &w : ck::availableWidths()) {
      // One guard triangle past the end: nothing is written beyond 2m − 1.
      std::vector<std::array<std::uint32_t, 3>> triangles(2 * m, {7, 7, 7});
      ck::zipRows(m, lower.data(), upper.data(), triangles[0].data(), w.id);
      EXPECT_EQ(triangles.back(), (std::array<std::uint32_t, 3>{7, 7, 7})) << w.name << " m " << m;
      triangles.pop_back();
      EXPECT_EQ(triangles, expected) << w.name << " m " << m;
    }
  }
}
