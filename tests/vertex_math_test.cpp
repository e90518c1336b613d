// Properties of curvenet/vertex_math.hpp, reproducing [SV14] Sec. 2 / App. A
// and [HPS09] Theorems 1–2, Lemmas 1–4. Every optimum is checked against an
// independent computation (brute-force scan, other parametrization, finite
// differences), never against the formulas under test.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "curvenet/error.hpp"
#include "curvenet/vertex_math.hpp"

using namespace curvenet;

namespace {

constexpr double pi = std::numbers::pi;

/// Distance of two line angles (mod π).
double lineAngleDistance(double a, double b) { return std::abs(std::remainder(a - b, pi)); }

struct Rng {
  std::mt19937_64 engine{20240611};
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(engine); }
};

CurvatureTensor randomTensor(Rng &rng) {
  return {rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-pi, pi)};
}

/// n directions, pairwise at least `gap` apart modulo π.
std::vector<double> randomDirections(Rng &rng, int n, double gap) {
  for (;;) {
    std::vector<double> w;
    for (int i = 0; i < n; ++i) w.push_back(rng.uniform(-pi, pi));
    bool ok = true;
    for (int i = 0; i < n; ++i)
      for (int j = i + 1; j < n; ++j) ok = ok && lineAngleDistance(w[i], w[j]) > gap;
    if (ok) return w;
  }
}

/// n angles between consecutive tangents, each in [margin, π − margin], summing to 2π.
std::vector<double> randomGaps(Rng &rng, int n, double margin) {
  for (;;) {
    std::vector<double> cut;
    for (int i = 0; i < n; ++i) cut.push_back(rng.uniform(0, 2 * pi));
    std::sort(cut.begin(), cut.end());
    std::vector<double> psi;
    for (int i = 0; i + 1 < n; ++i) psi.push_back(cut[i + 1] - cut[i]);
    psi.push_back(2 * pi - (cut.back() - cut.front()));
    if (std::all_of(psi.begin(), psi.end(), [&](double p) { return p > margin && p < pi - margin; })) return psi;
  }
}

/// φ_i of [HPS09] Definition 2, measured from `start`.
std::vector<double> tangentAngles(const std::vector<double> &psi, double start) {
  std::vector<double> phi;
  double a = start;
  for (double p : psi) {
    phi.push_back(a);
    a += p;
  }
  return phi;
}

double sumSquares(const CurvatureTensor &t, const std::vector<double> &w, const std::vector<double> &k) {
  double s = 0;
  for (std::size_t i = 0; i < w.size(); ++i) s += std::pow(t.normalCurvature(w[i]) - k[i], 2);
  return s;
}

void expectSameTensor(const CurvatureTensor &got, const CurvatureTensor &want, double tol) {
  EXPECT_NEAR(got.k1, want.k1, tol);
  EXPECT_NEAR(got.k2, want.k2, tol);
  if (std::abs(want.k1 - want.k2) > 1e-3) {
    EXPECT_LT(lineAngleDistance(got.lambda, want.lambda), tol * 100);
  }
}

CurvatureTensor orderedTensor(CurvatureTensor t) { return CurvatureTensor::fromWeingarten(t.toWeingarten()); }

/// Eq. (8) objective 1/κ1² + 1/κ2² of a form.
double radiusObjective(const WeingartenForm &w) {
  const double det = w.w1 * w.w2 - w.w12 * w.w12;
  return (w.w1 * w.w1 + w.w2 * w.w2 + 2 * w.w12 * w.w12) / (det * det);
}

/// The line of forms with κ(ω1) = k1, κ(ω2) = k2 (eq. 7), parametrized
/// independently of App. A: the least-norm solution plus t times the null vector.
struct ConstraintLine {
  Eigen::Vector3d base, dir;
  ConstraintLine(double w1, double k1, double w2, double k2) {
    Eigen::Matrix<double, 2, 3> A;
    A << std::pow(std::cos(w1), 2), std::pow(std::sin(w1), 2), std::sin(2 * w1), //
        std::pow(std::cos(w2), 2), std::pow(std::sin(w2), 2), std::sin(2 * w2);
    base = A.completeOrthogonalDecomposition().solve(Eigen::Vector2d(k1, k2));
    dir = Eigen::Vector3d(A.row(0)).cross(Eigen::Vector3d(A.row(1))).normalized();
  }
  WeingartenForm at(double t) const {
    const Eigen::Vector3d v = base + t * dir;
    return {v(0), v(1), v(2)};
  }
  double parameterOf(const WeingartenForm &w) const { return (Eigen::Vector3d(w.w1, w.w2, w.w12) - base).dot(dir); }
};

struct ScanMinimum {
  bool found = false;
  double t = 0, value = std::numeric_limits<double>::infinity();
};

double gaussian(const WeingartenForm &w) { return w.w1 * w.w2 - w.w12 * w.w12; }

/// Smallest discrete local minimum of eq. (8) along the line over [−T, T];
/// with ellipticOnly, among samples with κ1κ2 > 0.
ScanMinimum scanLocalMinima(const ConstraintLine &line, double T, int samples, bool ellipticOnly = false) {
  std::vector<double> f(samples);
  const double h = 2 * T / (samples - 1);
  for (int i = 0; i < samples; ++i) {
    const WeingartenForm w = line.at(-T + i * h);
    f[i] = ellipticOnly && gaussian(w) <= 0 ? std::numeric_limits<double>::infinity() : radiusObjective(w);
  }
  ScanMinimum best;
  for (int i = 1; i + 1 < samples; ++i)
    if (std::isfinite(f[i]) && f[i] < f[i - 1] && f[i] < f[i + 1] && f[i] < best.value) best = {true, -T + i * h, f[i]};
  return best;
}

} // namespace

// ---------------------------------------------------------------------------
// Representations: eqs. (1), (3)–(6)
// ---------------------------------------------------------------------------

TEST(CurvatureTensor, EulerFormulaAgreesWithWeingartenFormAndRoundTrips) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const CurvatureTensor t = randomTensor(rng);
    const WeingartenForm w = t.toWeingarten();
    for (int j = 0; j < 8; ++j) {
      const double omega = rng.uniform(-4, 4);
      EXPECT_NEAR(t.normalCurvature(omega), w.normalCurvature(omega), 1e-13);
    }
    const CurvatureTensor back = CurvatureTensor::fromWeingarten(w);
    EXPECT_GE(back.k1, back.k2);
    EXPECT_GT(back.lambda, -pi / 2);
    EXPECT_LE(back.lambda, pi / 2);
    EXPECT_NEAR(back.k1, std::max(t.k1, t.k2), 1e-13);
    EXPECT_NEAR(back.k2, std::min(t.k1, t.k2), 1e-13);
    // The k1 principal direction is where κ is largest.
    EXPECT_NEAR(back.normalCurvature(back.lambda), back.k1, 1e-13);
    for (int j = 0; j < 8; ++j) {
      const double omega = rng.uniform(-4, 4);
      EXPECT_NEAR(back.normalCurvature(omega), t.normalCurvature(omega), 1e-13);
    }
  }
  const CurvatureTensor umbilic = CurvatureTensor::fromWeingarten({0.5, 0.5, 0});
  EXPECT_EQ(umbilic.k1, 0.5);
  EXPECT_EQ(umbilic.k2, 0.5);
  EXPECT_EQ(umbilic.lambda, 0.0);
}

// ---------------------------------------------------------------------------
// [SV14] Sec. 2 fits
// ---------------------------------------------------------------------------

TEST(FitCurvature, ThreeDirectionsRecoverTheTensorExactly) {
  Rng rng;
  for (int trial = 0; trial < 200; ++trial) {
    const CurvatureTensor truth = orderedTensor(randomTensor(rng));
    const std::vector<double> w = randomDirections(rng, 3, 0.2);
    std::vector<double> k;
    for (double o : w) k.push_back(truth.normalCurvature(o));
    const CurvatureFit fit = fitCurvature(w, k);
    EXPECT_EQ(fit.branch, FitBranch::Exact);
    EXPECT_EQ(fit.independentDirections, 3);
    expectSameTensor(fit.tensor, truth, 1e-10);
    EXPECT_LT(fit.maxResidual, 1e-12);
  }
}

// [HPS09] Lemma 1: three pairwise non-parallel tangents determine κ1, κ2 and
// d, through the paper's own system T w = κ‖t‖² with t1 = (1, 0).
TEST(FitCurvature, Lemma1ThreeTangentsDetermineCurvatureAndDirection) {
  Rng rng;
  for (int trial = 0; trial < 100; ++trial) {
    const CurvatureTensor truth = orderedTensor(randomTensor(rng));
    std::vector<double> w = randomDirections(rng, 3, 0.2);
    // Lemma 1's frame has t1 along x; rotate the directions so.
    const double base = w[0];
    for (double &o : w) o -= base;
    const CurvatureTensor local{truth.k1, truth.k2, truth.lambda - base};
    std::vector<double> k;
    for (double o : w) k.push_back(local.normalCurvature(o));

    // The paper's system with non-unit tangents t_i = r_i (cos ω_i, sin ω_i).
    Eigen::Matrix3d T;
    Eigen::Vector3d rhs;
    for (int i = 0; i < 3; ++i) {
      const double r = i == 0 ? 1.0 : rng.uniform(0.5, 3);
      const double x = r * std::cos(w[i]), y = r * std::sin(w[i]);
      T.row(i) << x * x, x * y, y * y;
      rhs(i) = k[i] * r * r;
    }
    EXPECT_GT(std::abs(T.determinant()), 1e-6);
    const Eigen::Vector3d sol = T.lu().solve(rhs);
    Eigen::Matrix2d W;
    W << sol(0), sol(1) / 2, sol(1) / 2, sol(2);
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eig(W);
    const double kappa1 = eig.eigenvalues()(1), kappa2 = eig.eigenvalues()(0);
    const Eigen::Vector2d d = eig.eigenvectors().col(1);

    const CurvatureFit fit = fitCurvature(w, k);
    EXPECT_EQ(fit.branch, FitBranch::Exact);
    EXPECT_NEAR(fit.tensor.k1, kappa1, 1e-10);
    EXPECT_NEAR(fit.tensor.k2, kappa2, 1e-10);
    if (kappa1 - kappa2 > 1e-3) {
      EXPECT_LT(lineAngleDistance(fit.tensor.lambda, std::atan2(d(1), d(0))), 1e-9);
    }
    expectSameTensor(fit.tensor, local, 1e-10);
  }
}

TEST(FitCurvature, FiveConsistentDirectionsRecoverTheTensorByLeastSquares) {
  Rng rng;
  for (int trial = 0; trial < 100; ++trial) {
    const CurvatureTensor truth = orderedTensor(randomTensor(rng));
    const std::vector<double> w = randomDirections(rng, 5, 0.1);
    std::vector<double> k;
    for (double o : w) k.push_back(truth.normalCurvature(o));
    const CurvatureFit fit = fitCurvature(w, k);
    EXPECT_EQ(fit.branch, FitBranch::LeastSquares);
    EXPECT_EQ(fit.independentDirections, 5);
    expectSameTensor(fit.tensor, truth, 1e-10);
    EXPECT_LT(fit.rmsResidual, 1e-12);
  }
}

// Inconsistent data: the fit must be the least-squares optimum of eq. (2).
// Independent check: for fixed λ eq. (2) is linear in (κ1, κ2); a dense scan
// over λ with a 2×2 solve each, refined by golden section, gives the optimum.
TEST(FitCurvature, FiveInconsistentDirectionsGiveTheLeastSquaresOptimum) {
  Rng rng;
  for (int trial = 0; trial < 30; ++trial) {
    const std::vector<double> w = randomDirections(rng, 5, 0.1);
    std::vector<double> k;
    for (int i = 0; i < 5; ++i) k.push_back(rng.uniform(-2, 2));
    const CurvatureFit fit = fitCurvature(w, k);
    ASSERT_EQ(fit.branch, FitBranch::LeastSquares);

    auto bestForLambda = [&](double lambda) {
      Eigen::Matrix<double, 5, 2> A;
      Eigen::Matrix<double, 5, 1> b;
      for (int i = 0; i < 5; ++i) {
        A(i, 0) = std::pow(std::cos(w[i] - lambda), 2);
        A(i, 1) = std::pow(std::sin(w[i] - lambda), 2);
        b(i) = k[i];
      }
      const Eigen::Vector2d x = (A.transpose() * A).ldlt().solve(A.transpose() * b);
      return std::make_pair((A * x - b).squaredNorm(), CurvatureTensor{x(0), x(1), lambda});
    };
    double bestLambda = 0, bestValue = std::numeric_limits<double>::infinity();
    const int samples = 20000;
    for (int i = 0; i < samples; ++i) {
      const double lambda = pi * i / samples;
      const double v = bestForLambda(lambda).first;
      if (v < bestValue) bestValue = v, bestLambda = lambda;
    }
    double lo = bestLambda - pi / samples, hi = bestLambda + pi / samples;
    for (int it = 0; it < 100; ++it) { // golden section
      const double m1 = lo + (hi - lo) * 0.382, m2 = lo + (hi - lo) * 0.618;
      if (bestForLambda(m1).first < bestForLambda(m2).first)
        hi = m2;
      else
        lo = m1;
    }
    const auto [scanValue, scanTensor] = bestForLambda(0.5 * (lo + hi));

    const double fitValue = sumSquares(fit.tensor, w, k);
    EXPECT_NEAR(fitValue, scanValue, 1e-10 * (1 + scanValue));
    EXPECT_NEAR(fit.rmsResidual, std::sqrt(fitValue / 5), 1e-12);
    expectSameTensor(fit.tensor, orderedTensor(scanTensor), 1e-6);

    // Finite-difference gradient in (κ1, κ2, λ) vanishes.
    const double h = 1e-6;
    for (int p = 0; p < 3; ++p) {
      CurvatureTensor plus = fit.tensor, minus = fit.tensor;
      (p == 0 ? plus.k1 : p == 1 ? plus.k2 : plus.lambda) += h;
      (p == 0 ? minus.k1 : p == 1 ? minus.k2 : minus.lambda) -= h;
      EXPECT_NEAR((sumSquares(plus, w, k) - sumSquares(minus, w, k)) / (2 * h), 0.0, 1e-7);
    }
    // And random perturbations never improve it.
    for (int j = 0; j < 50; ++j) {
      CurvatureTensor p = fit.tensor;
      p.k1 += rng.uniform(-1e-3, 1e-3);
      p.k2 += rng.uniform(-1e-3, 1e-3);
      p.lambda += rng.uniform(-1e-3, 1e-3);
      EXPECT_GE(sumSquares(p, w, k), fitValue - 1e-14);
    }
  }
}

// n = 2, same-sign curvatures: eq. (7) holds and the result is the elliptic
// minimum of eq. (8) along the constraint line, found by a dense scan.
TEST(FitCurvature, TwoDirectionsCubicGivesTheEllipticMinimumOfRadiusObjective) {
  Rng rng;
  std::vector<std::array<double, 4>> cases; // ω1, k1, ω2, k2
  for (int trial = 0; trial < 60; ++trial) {
    const std::vector<double> w = randomDirections(rng, 2, 0.15);
    const double sign = trial % 2 ? 1.0 : -1.0;
    cases.push_back({w[0], sign * rng.uniform(0.2, 2), w[1], sign * rng.uniform(0.2, 2)});
  }
  // d = s2²c1² − s1²c2² of App. A is zero for these in the given frame.
  cases.push_back({-pi / 6, 1.0, pi / 6, 0.4});
  cases.push_back({0.3, 0.5, pi - 0.3, 1.5});
  cases.push_back({0.3, 0.5, -0.3, 1.5});
  cases.push_back({pi / 4, 2.0, -pi / 4, 0.7});
  cases.push_back({0.0, 1.0, pi / 2, 3.0});
  // Eq. (8) has a smaller, hyperbolic, local minimum here (checked below).
  cases.push_back({-0.458373, 1.16328, -0.384985, 1.27255});

  for (const auto &[w1, k1, w2, k2] : cases) {
    SCOPED_TRACE(testing::Message() << "omega " << w1 << ", " << w2 << " k " << k1 << ", " << k2);
    const std::vector<double> w{w1, w2}, k{k1, k2};
    const CurvatureFit fit = fitCurvature(w, k);
    ASSERT_EQ(fit.branch, FitBranch::Underdetermined);
    EXPECT_EQ(fit.independentDirections, 2);
    EXPECT_NEAR(fit.tensor.normalCurvature(w1), k1, 1e-12);
    EXPECT_NEAR(fit.tensor.normalCurvature(w2), k2, 1e-12);
    EXPECT_LT(fit.maxResidual, 1e-12);
    EXPECT_GT(fit.tensor.gaussianCurvature(), 0.0);

    const ConstraintLine line(w1, k1, w2, k2);
    const WeingartenForm form = fit.tensor.toWeingarten();
    const double t0 = line.parameterOf(form);
    const double f0 = radiusObjective(form);
    EXPECT_NEAR(f0, 1 / std::pow(fit.tensor.k1, 2) + 1 / std::pow(fit.tensor.k2, 2), 1e-9 * f0);
    // Local minimum: no smaller value nearby on the line.
    for (double h : {1e-5, 1e-4, 1e-3}) {
      EXPECT_GE(radiusObjective(line.at(t0 + h)), f0 * (1 - 1e-12));
      EXPECT_GE(radiusObjective(line.at(t0 - h)), f0 * (1 - 1e-12));
    }
    // Dense scan: the smallest elliptic local minimum sits where the cubic put it.
    const double scale = std::max(std::abs(k1), std::abs(k2));
    const double T = 20 * scale, step = 2 * T / 400000;
    const ScanMinimum scan = scanLocalMinima(line, T, 400001, true);
    ASSERT_TRUE(scan.found);
    EXPECT_NEAR(t0, scan.t, 2 * step);
    EXPECT_LE(f0, scan.value * (1 + 1e-9));
  }
  // The hyperbolic minimum that the elliptic rule passes over.
  const ConstraintLine line(-0.458373, 1.16328, -0.384985, 1.27255);
  const ScanMinimum any = scanLocalMinima(line, 40, 400001);
  const CurvatureFit fit = fitCurvature(std::vector<double>{-0.458373, -0.384985}, std::vector<double>{1.16328, 1.27255});
  ASSERT_TRUE(any.found);
  EXPECT_LT(any.value, radiusObjective(fit.tensor.toWeingarten()));
  EXPECT_LT(gaussian(line.at(any.t)), 0.0);
}

// k1·k2 < 0: every interpolant is hyperbolic. The case ω = (0, π/2), k = (1,
// −1) has the closed form f = 2/(1 + W12²): no minimum, one stationary point
// W12 = 0, i.e. κ = (1, −1) along the curves. In general the result is the
// maximum of eq. (8) along the constraint line.
TEST(FitCurvature, TwoDirectionsOppositeSignsGiveTheLeastCurvedSaddle) {
  {
    const std::vector<double> w{0.0, pi / 2}, k{1.0, -1.0};
    const CurvatureFit fit = fitCurvature(w, k);
    EXPECT_EQ(fit.branch, FitBranch::UnderdeterminedSaddle);
    EXPECT_NEAR(fit.tensor.k1, 1.0, 1e-12);
    EXPECT_NEAR(fit.tensor.k2, -1.0, 1e-12);
    EXPECT_LT(lineAngleDistance(fit.tensor.lambda, 0.0), 1e-12);
  }
  Rng rng;
  for (int trial = 0; trial < 40; ++trial) {
    const std::vector<double> w = randomDirections(rng, 2, 0.15);
    const std::vector<double> k{rng.uniform(0.2, 2), -rng.uniform(0.2, 2)};
    SCOPED_TRACE(testing::Message() << "omega " << w[0] << ", " << w[1] << " k " << k[0] << ", " << k[1]);
    const CurvatureFit fit = fitCurvature(w, k);
    ASSERT_EQ(fit.branch, FitBranch::UnderdeterminedSaddle);
    EXPECT_LT(fit.maxResidual, 1e-12);
    EXPECT_LT(fit.tensor.gaussianCurvature(), 0.0);
    const ConstraintLine line(w[0], k[0], w[1], k[1]);
    const double t0 = line.parameterOf(fit.tensor.toWeingarten());
    const double f0 = radiusObjective(line.at(t0)), h = 1e-5;
    // Stationary (central difference) ...
    EXPECT_NEAR((radiusObjective(line.at(t0 + h)) - radiusObjective(line.at(t0 - h))) / (2 * h), 0.0, 1e-6 * f0);
    // ... and the maximum over a dense scan of the line.
    double scanMax = 0;
    for (int i = 0; i <= 200000; ++i) scanMax = std::max(scanMax, radiusObjective(line.at(-100 + i * 1e-3)));
    EXPECT_LE(scanMax, f0 * (1 + 1e-12));
    EXPECT_GE(scanMax, f0 * (1 - 1e-4));
  }
}

// Nearly parallel curves with different curvatures need huge, very
// anisotropic interpolants (κ1 ~ Δk/gap², κ2 ~ the data). App. A's expanded
// coefficients cancel catastrophically there; the fit must stay accurate.
TEST(FitCurvature, TwoNearlyParallelDirectionsStayAccurate) {
  struct Case {
    double omega, gap, k1, k2;
  };
  for (const Case &c : {Case{0.3, 1e-4, 1.0, 1.5}, Case{-1.0, 1e-3, 100.0, 0.01}, Case{2.0, 3.38794e-06, 163.854, 0.0493592},
                        Case{0.7, 1e-5, -2.0, -0.5}, Case{1.1, 1e-4, 3.0, -0.2}}) {
    SCOPED_TRACE(testing::Message() << "gap " << c.gap << " k " << c.k1 << ", " << c.k2);
    const std::vector<double> w{c.omega, c.omega + c.gap}, k{c.k1, c.k2};
    const CurvatureFit fit = fitCurvature(w, k);
    const double scale = std::max(std::abs(c.k1), std::abs(c.k2));
    EXPECT_NEAR(fit.tensor.normalCurvature(w[0]), c.k1, 1e-9 * scale);
    EXPECT_NEAR(fit.tensor.normalCurvature(w[1]), c.k2, 1e-9 * scale);
    if (c.k1 * c.k2 > 0) {
      EXPECT_EQ(fit.branch, FitBranch::Underdetermined);
      EXPECT_GT(fit.tensor.gaussianCurvature(), 0.0);
    } else {
      EXPECT_EQ(fit.branch, FitBranch::UnderdeterminedSaddle);
      EXPECT_LT(fit.tensor.gaussianCurvature(), 0.0);
    }
    EXPECT_GT(std::max(std::abs(fit.tensor.k1), std::abs(fit.tensor.k2)), scale * 0.1 / c.gap);
  }
}

TEST(FitCurvature, UmbilicException) {
  const std::vector<double> w{0.2, 1.3}, k{0.7, 0.7};
  const CurvatureFit fit = fitCurvature(w, k);
  EXPECT_EQ(fit.branch, FitBranch::Umbilic);
  EXPECT_EQ(fit.tensor.k1, 0.7);
  EXPECT_EQ(fit.tensor.k2, 0.7);
  EXPECT_EQ(fit.tensor.lambda, 0.0);
  EXPECT_EQ(fit.maxResidual, 0.0);

  // The exception is a prescription of [SV14], not the minimizer of eq. (8):
  // for non-orthogonal curves the umbilic is not stationary along the line,
  // and barely non-umbilic data take the cubic to a better value.
  const ConstraintLine line(w[0], k[0], w[1], k[1]);
  const double t0 = line.parameterOf(fit.tensor.toWeingarten()), h = 1e-6;
  EXPECT_GT(std::abs(radiusObjective(line.at(t0 + h)) - radiusObjective(line.at(t0 - h))) / (2 * h), 1e-2);
  const std::vector<double> kNear{0.7, 0.7 * (1 + 1e-6)};
  const CurvatureFit near = fitCurvature(w, kNear);
  EXPECT_EQ(near.branch, FitBranch::Underdetermined);
  EXPECT_LT(radiusObjective(near.tensor.toWeingarten()), radiusObjective(fit.tensor.toWeingarten()));

  // Orthogonal curves: the umbilic is the minimizer, so both branches agree.
  const std::vector<double> wo{0.2, 0.2 + pi / 2};
  const CurvatureFit ortho = fitCurvature(wo, kNear);
  EXPECT_EQ(ortho.branch, FitBranch::Underdetermined);
  EXPECT_NEAR(ortho.tensor.k1, 0.7, 1e-6);
  EXPECT_NEAR(ortho.tensor.k2, 0.7, 1e-6);
}

TEST(FitCurvature, ZeroCurvatureException) {
  const double wz = 0.4, wo = 1.5, s2 = std::pow(std::sin(wo - wz), 2);
  {
    const std::vector<double> w{wz, wo}, k{0.0, 0.8};
    const CurvatureFit fit = fitCurvature(w, k);
    EXPECT_EQ(fit.branch, FitBranch::ZeroCurvature);
    EXPECT_NEAR(fit.tensor.k1, 0.8 / s2, 1e-14);
    EXPECT_EQ(fit.tensor.k2, 0.0);
    EXPECT_LT(lineAngleDistance(fit.tensor.lambda, wz + pi / 2), 1e-14);
    EXPECT_LT(fit.maxResidual, 1e-14);
  }
  {
    // Negative curvature: by k1 ≥ k2 the zero one is now κ1, along the flat curve.
    const std::vector<double> w{wo, wz}, k{-0.8, 0.0};
    const CurvatureFit fit = fitCurvature(w, k);
    EXPECT_EQ(fit.branch, FitBranch::ZeroCurvature);
    EXPECT_EQ(fit.tensor.k1, 0.0);
    EXPECT_NEAR(fit.tensor.k2, -0.8 / s2, 1e-14);
    EXPECT_LT(lineAngleDistance(fit.tensor.lambda, wz), 1e-14);
    EXPECT_LT(fit.maxResidual, 1e-14);
  }
  // The exception is the limit of the cubic from both sides of k = 0, also for
  // close directions (where eq. (8) has hyperbolic minima far from it).
  for (double other : {wo, wz + 0.3, wz - 0.2, wz + 2.5}) {
    const double sin2 = std::pow(std::sin(other - wz), 2);
    for (double eps : {1e-6, -1e-6}) {
      SCOPED_TRACE(testing::Message() << "omega " << other << " eps " << eps);
      const std::vector<double> w{wz, other}, k{eps, 0.8};
      const CurvatureFit fit = fitCurvature(w, k);
      EXPECT_EQ(fit.branch, eps > 0 ? FitBranch::Underdetermined : FitBranch::UnderdeterminedSaddle);
      EXPECT_NEAR(fit.tensor.k1, 0.8 / sin2, 1e-4 / sin2);
      EXPECT_NEAR(fit.tensor.k2, 0.0, 1e-4);
      EXPECT_LT(lineAngleDistance(fit.tensor.lambda, wz + pi / 2), 1e-4);
    }
  }
}

TEST(FitCurvature, XNodeCountsTwoIndependentCurves) {
  // Both legs of each through-curve carry the same direction mod π (Fig. 1).
  const CurvatureTensor truth = orderedTensor({1.2, 0.3, 0.5});
  const std::vector<double> w{0.1, 0.1 + pi, 1.2, 1.2 - pi};
  std::vector<double> k;
  for (double o : w) k.push_back(truth.normalCurvature(o));
  const CurvatureFit fit = fitCurvature(w, k);
  EXPECT_EQ(fit.independentDirections, 2);
  EXPECT_EQ(fit.branch, FitBranch::Underdetermined);
  EXPECT_LT(fit.maxResidual, 1e-12);
  // Legs that disagree: each curve is matched by its mean (the LS value).
  const std::vector<double> kBad{1.0, 0.8, 0.5, 0.5};
  const CurvatureFit bad = fitCurvature(w, kBad);
  EXPECT_NEAR(bad.tensor.normalCurvature(0.1), 0.9, 1e-12);
  EXPECT_NEAR(bad.maxResidual, 0.1, 1e-12);
  EXPECT_NEAR(bad.rmsResidual, std::sqrt(0.02 / 4), 1e-12);
}

TEST(FitCurvature, SingleDirectionAndBadInput) {
  const std::vector<double> w{0.3, 0.3 + pi}, k{0.5, 0.7};
  const CurvatureFit fit = fitCurvature(w, k);
  EXPECT_EQ(fit.branch, FitBranch::SingleDirection);
  EXPECT_EQ(fit.independentDirections, 1);
  EXPECT_NEAR(fit.tensor.k1, 0.6, 1e-15);
  EXPECT_NEAR(fit.tensor.k2, 0.6, 1e-15);

  const std::vector<double> one{0.1};
  EXPECT_THROW(fitCurvature(w, one), InputError);
  EXPECT_THROW(fitCurvature(std::vector<double>{}, std::vector<double>{}), InputError);
  const std::vector<double> nan{0.1, std::nan("")};
  EXPECT_THROW(fitCurvature(w, nan), InputError);
}

// ---------------------------------------------------------------------------
// [SV14] constrained fit (Sec. 2 (iv), App. A)
// ---------------------------------------------------------------------------

TEST(FitCurvatureConstrained, MatchesTheConstraintAndIsOptimalAlongIt) {
  Rng rng;
  for (int trial = 0; trial < 50; ++trial) {
    const std::vector<double> all = randomDirections(rng, 7, 0.1);
    const double omega0 = all[0], k0 = rng.uniform(-2, 2);
    const std::vector<double> w(all.begin() + 1, all.end());
    std::vector<double> k;
    for (std::size_t i = 0; i < w.size(); ++i) k.push_back(rng.uniform(-2, 2));

    const CurvatureFit fit = fitCurvatureConstrained(w, k, omega0, k0);
    EXPECT_EQ(fit.branch, FitBranch::Constrained);
    EXPECT_NEAR(fit.tensor.normalCurvature(omega0), k0, 1e-12);
    const double value = sumSquares(fit.tensor, w, k);
    EXPECT_NEAR(fit.rmsResidual, std::sqrt(value / double(w.size())), 1e-12);

    // Independent solver: eliminate the constraint (null-space method).
    const Eigen::RowVector3d a(std::pow(std::cos(omega0), 2), std::pow(std::sin(omega0), 2), std::sin(2 * omega0));
    const Eigen::Vector3d particular = a.transpose() * (k0 / a.squaredNorm());
    Eigen::Matrix<double, 3, 2> N;
    {
      Eigen::JacobiSVD<Eigen::Matrix<double, 1, 3>> svd(a, Eigen::ComputeFullV);
      N = svd.matrixV().rightCols<2>();
    }
    Eigen::MatrixXd A(w.size(), 3);
    Eigen::VectorXd b(w.size());
    for (std::size_t i = 0; i < w.size(); ++i) {
      A.row(i) << std::pow(std::cos(w[i]), 2), std::pow(std::sin(w[i]), 2), std::sin(2 * w[i]);
      b(i) = k[i];
    }
    const Eigen::Vector2d z = (A * N).colPivHouseholderQr().solve(b - A * particular);
    const Eigen::Vector3d ref = particular + N * z;
    const WeingartenForm got = fit.tensor.toWeingarten();
    EXPECT_NEAR(got.w1, ref(0), 1e-10);
    EXPECT_NEAR(got.w2, ref(1), 1e-10);
    EXPECT_NEAR(got.w12, ref(2), 1e-10);

    // Scan the constraint plane around the result: nothing is better.
    const Eigen::Vector3d x0(got.w1, got.w2, got.w12);
    for (int i = -20; i <= 20; ++i)
      for (int j = -20; j <= 20; ++j) {
        const Eigen::Vector3d x = x0 + N * Eigen::Vector2d(0.01 * i, 0.01 * j);
        const WeingartenForm f{x(0), x(1), x(2)};
        EXPECT_NEAR(f.normalCurvature(omega0), k0, 1e-12);
        double s = 0;
        for (std::size_t m = 0; m < w.size(); ++m) s += std::pow(f.normalCurvature(w[m]) - k[m], 2);
        EXPECT_GE(s, value - 1e-12);
      }
  }
}

TEST(FitCurvatureConstrained, ConsistentDataAreRecoveredAndPaperRowWouldMissTheConstraint) {
  Rng rng;
  const CurvatureTensor truth = orderedTensor(randomTensor(rng));
  const std::vector<double> all = randomDirections(rng, 5, 0.2);
  const double omega0 = all[0];
  const std::vector<double> w(all.begin() + 1, all.end());
  std::vector<double> k;
  for (double o : w) k.push_back(truth.normalCurvature(o));
  const CurvatureFit fit = fitCurvatureConstrained(w, k, omega0, truth.normalCurvature(omega0));
  expectSameTensor(fit.tensor, truth, 1e-10);
  EXPECT_LT(fit.maxResidual, 1e-12);

  // App. A prints the constraint row as [c0², s0², s0 c0]; that row imposes
  // W1c0² + W2s0² + W12 s0c0 = k0, not κ(ω0) = k0 (eq. 6). With inconsistent
  // data the literal system misses the constraint; ours does not.
  std::vector<double> kBad = k;
  kBad[0] += 0.5;
  const double c0 = std::cos(omega0), s0 = std::sin(omega0), k0 = truth.normalCurvature(omega0);
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs(k0, 0, 0, 0);
  M.row(0) << c0 * c0, s0 * s0, s0 * c0, 0;
  for (std::size_t i = 0; i < w.size(); ++i) {
    const double c = std::cos(w[i]), s = std::sin(w[i]);
    M.row(1) += Eigen::RowVector4d(2 * c * c * c * c, 2 * s * s * c * c, 4 * s * c * c * c, 0);
    M.row(2) += Eigen::RowVector4d(2 * s * s * c * c, 2 * s * s * s * s, 4 * s * s * s * c, 0);
    M.row(3) += Eigen::RowVector4d(2 * s * c * c * c, 2 * s * s * s * c, 4 * s * s * c * c, 0);
    rhs.tail<3>() += Eigen::Vector3d(2 * c * c, 2 * s * s, 2 * s * c) * kBad[i];
  }
  M.block<3, 1>(1, 3) = Eigen::Vector3d(c0 * c0, s0 * s0, s0 * c0);
  const Eigen::Vector4d x = M.fullPivLu().solve(rhs);
  const WeingartenForm literal{x(0), x(1), x(2)};
  ASSERT_GT(std::abs(s0 * c0), 1e-3); // the typo only matters when W12 enters the constraint
  EXPECT_GT(std::abs(literal.normalCurvature(omega0) - k0), 1e-6);
  EXPECT_NEAR(fitCurvatureConstrained(w, kBad, omega0, k0).tensor.normalCurvature(omega0), k0, 1e-12);
}

TEST(FitCurvatureConstrained, NeedsTwoDirectionsBesidesTheConstraint) {
  const std::vector<double> w{0.5, 0.5 + pi, 1.0}, k{1, 1, 2};
  EXPECT_NO_THROW(fitCurvatureConstrained(w, k, 2.0, 0.3));
  EXPECT_THROW(fitCurvatureConstrained(w, k, 1.0, 0.3), InputError); // only ω = 0.5 is left
  const std::vector<double> w2{0.5, 0.5 + pi}, k2{1, 1};
  EXPECT_THROW(fitCurvatureConstrained(w2, k2, 2.0, 0.3), InputError);
}

// ---------------------------------------------------------------------------
// [HPS09]
// ---------------------------------------------------------------------------

TEST(Enclosure, OddValenceHasNoConstraint) {
  // Theorem 1: exactly zero whatever the curvatures.
  Rng rng;
  for (int n : {3, 5, 7}) {
    const std::vector<double> psi = randomGaps(rng, n, 0.05);
    std::vector<double> kappa;
    for (int i = 0; i < n; ++i) kappa.push_back(rng.uniform(-3, 3));
    const EnclosureResidual r = enclosureResidual(psi, kappa);
    EXPECT_EQ(r.raw, 0.0);
    EXPECT_EQ(r.normalized, 0.0);
  }
}

TEST(Enclosure, AgreesWithTheAlternatingDifferenceForm) {
  // Eq. (7) rewrites (6) as Σ (−1)^i (κ_i − κ_{i+1}) cot ψ_i; computed here
  // independently. Generic data violate the constraint.
  Rng rng;
  for (int n : {4, 6, 8}) {
    for (int trial = 0; trial < 20; ++trial) {
      const std::vector<double> psi = randomGaps(rng, n, 0.1);
      std::vector<double> kappa;
      for (int i = 0; i < n; ++i) kappa.push_back(rng.uniform(-3, 3));
      double eq7 = 0;
      for (int i = 1; i <= n; ++i)
        eq7 += (i % 2 ? -1.0 : 1.0) * (kappa[i - 1] - kappa[i % n]) / std::tan(psi[i - 1]);
      const EnclosureResidual r = enclosureResidual(psi, kappa);
      EXPECT_NEAR(r.raw, eq7, 1e-10 * (1 + std::abs(eq7)));
      double scale = 0;
      for (double x : kappa) scale = std::max(scale, std::abs(x));
      EXPECT_NEAR(r.normalized, std::abs(r.raw) / scale, 1e-15);
    }
  }
}

TEST(Enclosure, Theorem2EulerImpliesEnclosure) {
  Rng rng;
  for (int n : {4, 6, 8}) {
    int violatedWhenPerturbed = 0;
    for (int trial = 0; trial < 100; ++trial) {
      const std::vector<double> psi = randomGaps(rng, n, 0.1);
      const CurvatureTensor surface = randomTensor(rng);
      const std::vector<double> phi = tangentAngles(psi, rng.uniform(-pi, pi));
      std::vector<double> kappa;
      for (double p : phi) kappa.push_back(surface.normalCurvature(p));
      EXPECT_LT(eulerResidual(psi, kappa).normalized, 1e-12);
      EXPECT_LT(enclosureResidual(psi, kappa).normalized, 1e-10) << "n = " << n;
      // Perturb one curvature: generically enclosure breaks.
      kappa[trial % n] += 0.3;
      if (enclosureResidual(psi, kappa).normalized > 1e-4) ++violatedWhenPerturbed;
    }
    EXPECT_GT(violatedWhenPerturbed, 90);
  }
}

// Lemma 2: n = 6, ψ = 2π/12 ×3 then 2π/4 ×3, κ = 0,0,0,0,1,1.
TEST(Enclosure, Lemma2EnclosureIsWeakerThanEuler) {
  const std::vector<double> psi{2 * pi / 12, 2 * pi / 12, 2 * pi / 12, 2 * pi / 4, 2 * pi / 4, 2 * pi / 4};
  const std::vector<double> kappa{0, 0, 0, 0, 1, 1};
  EXPECT_LT(enclosureResidual(psi, kappa).normalized, 1e-14);
  const EulerResidual euler = eulerResidual(psi, kappa);
  EXPECT_GT(euler.normalized, 0.1);
  // The first three curves alone (Lemma 1) force the zero tensor.
  const CurvatureFit three = fitCurvature(std::vector<double>{0, pi / 6, pi / 3}, std::vector<double>{0, 0, 0});
  EXPECT_EQ(three.tensor.k1, 0.0);
  EXPECT_EQ(three.tensor.k2, 0.0);
}

// Lemma 3: an X. (6) holds automatically for any κ; (26) requires κ1 = κ3 and
// κ2 = κ4, so κ = 0,0,0,1 satisfies (6) but not (26).
TEST(Enclosure, Lemma3XSatisfiesEnclosureButNotEuler) {
  Rng rng;
  for (double a : {pi / 2, 1.1, 0.3, 2.5}) {
    const std::vector<double> psi{a, pi - a, a, pi - a};
    EXPECT_TRUE(formsX(psi));
    const std::vector<double> kappa{0, 0, 0, 1};
    EXPECT_LT(enclosureResidual(psi, kappa).normalized, 1e-14);
    EXPECT_GT(eulerResidual(psi, kappa).normalized, 0.1);
    // Enclosure without restriction on the κ_i ...
    for (int trial = 0; trial < 20; ++trial) {
      std::vector<double> any;
      for (int i = 0; i < 4; ++i) any.push_back(rng.uniform(-3, 3));
      EXPECT_LT(enclosureResidual(psi, any).normalized, 1e-14);
    }
    // ... while Euler holds exactly when opposite curvatures agree (32).
    const std::vector<double> paired{0.3, -0.5, 0.3, -0.5};
    EXPECT_LT(eulerResidual(psi, paired).normalized, 1e-12);
  }
}

TEST(Enclosure, FormsXDetection) {
  EXPECT_TRUE(formsX(std::vector<double>{1.0, pi - 1.0, 1.0, pi - 1.0}));
  EXPECT_FALSE(formsX(std::vector<double>{1.0, pi - 1.0 + 1e-3, 1.0 - 1e-3, pi - 1.0}));
  EXPECT_TRUE(formsX(std::vector<double>{1.0, pi - 1.0 + 1e-3, 1.0 - 1e-3, pi - 1.0}, 2e-3));
  // One collinear pair only (a T-like crossing) is not an X.
  EXPECT_FALSE(formsX(std::vector<double>{1.0, pi - 1.0, 0.5, pi - 0.5}));
  EXPECT_FALSE(formsX(std::vector<double>{2 * pi / 3, 2 * pi / 3, 2 * pi / 3}));
  EXPECT_FALSE(formsX(std::vector<double>{pi / 3, pi / 3, pi / 3, pi / 3, pi / 3, pi / 3}));
}

// Lemma 4: n = 4 not forming an X: (6) ⇔ (26).
TEST(Enclosure, Lemma4FourCurvesEnclosureIffEuler) {
  Rng rng;
  int tested = 0;
  while (tested < 200) {
    const std::vector<double> psi = randomGaps(rng, 4, 0.1);
    // Keep away from X-like configurations, where (6) degenerates.
    if (std::abs(std::sin(psi[0] + psi[1])) < 0.1 || std::abs(std::sin(psi[1] + psi[2])) < 0.1) continue;
    ASSERT_FALSE(formsX(psi));
    ++tested;

    // Euler ⇒ enclosure.
    const CurvatureTensor surface = randomTensor(rng);
    std::vector<double> kappa;
    for (double p : tangentAngles(psi, rng.uniform(-pi, pi))) kappa.push_back(surface.normalCurvature(p));
    EXPECT_LT(enclosureResidual(psi, kappa).normalized, 1e-10);

    // Enclosure ⇒ Euler: random κ1..κ3, κ4 solved from (6) (it enters linearly).
    std::vector<double> k{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2), 0.0};
    const double r0 = enclosureResidual(psi, k).raw;
    k[3] = 1.0;
    const double coefficient = enclosureResidual(psi, k).raw - r0;
    k[3] = -r0 / coefficient;
    EXPECT_LT(enclosureResidual(psi, k).normalized, 1e-10);
    const EulerResidual euler = eulerResidual(psi, k);
    EXPECT_LT(euler.normalized, 1e-9);
    // The Euler fit reproduces every κ_i (φ measured from tangent 1).
    const std::vector<double> phi = tangentAngles(psi, 0.0);
    for (int i = 0; i < 4; ++i) EXPECT_NEAR(euler.fit.normalCurvature(phi[i]), k[i], 1e-9 * (1 + std::abs(k[i])));

    // Contrapositive: breaking enclosure breaks Euler.
    k[3] += 0.5;
    EXPECT_GT(eulerResidual(psi, k).rms, 1e-4);
  }
}

TEST(Enclosure, ThreeCurvesAlwaysSatisfyEuler) {
  // Lemma 1 again, through eulerResidual.
  Rng rng;
  for (int trial = 0; trial < 20; ++trial) {
    const std::vector<double> psi = randomGaps(rng, 3, 0.1);
    const std::vector<double> kappa{rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-2, 2)};
    EXPECT_LT(eulerResidual(psi, kappa).normalized, 1e-12);
  }
}

TEST(Enclosure, RejectsMalformedAngles) {
  const std::vector<double> k4{0, 0, 0, 0};
  EXPECT_THROW(enclosureResidual(std::vector<double>{1, 1, 1, 1}, k4), InputError);           // Σ ≠ 2π
  EXPECT_THROW(enclosureResidual(std::vector<double>{pi, pi / 2, pi / 4, pi / 4}, k4), InputError); // ψ = π
  EXPECT_THROW(enclosureResidual(std::vector<double>{pi / 2, pi / 2, pi / 2, pi / 2}, std::vector<double>{0, 0}),
               InputError);
  EXPECT_THROW(eulerResidual(std::vector<double>{pi, pi}, std::vector<double>{0, 0}), InputError);
  EXPECT_THROW(formsX(std::vector<double>{1, 1, 1, 1}), InputError);
}
