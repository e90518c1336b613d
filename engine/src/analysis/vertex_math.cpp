// Surface curvature at a vertex: [SV14] Sec. 2 / App. A and [HPS09] eqs. (6),
// (26). See curvenet/vertex_math.hpp for the conventions.
#include "curvenet/vertex_math.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "analysis/vertex_curvature.hpp"
#include "curvenet/error.hpp"

namespace curvenet {
inline namespace v1 {

namespace {

constexpr double pi = std::numbers::pi;
constexpr double invSqrt2 = 1.0 / std::numbers::sqrt2;

/// Angle of a line, reduced to (−π/2, π/2].
double wrapLineAngle(double a) {
  a = std::remainder(a, pi); // [−π/2, π/2]
  return a <= -0.5 * pi ? a + pi : a;
}

/// Principal pair with the k1 ≥ k2 convention; `lambdaA` is the direction of `ka`.
CurvatureTensor ordered(double ka, double kb, double lambdaA) {
  if (ka >= kb) return {ka, kb, wrapLineAngle(ka == kb ? 0.0 : lambdaA)};
  return {kb, ka, wrapLineAngle(lambdaA + 0.5 * pi)};
}

/// One row of [SV14] eq. (6): κ(ω) = [cos²ω, sin²ω, 2 sinω cosω] · (W1, W2, W12).
Eigen::RowVector3d eulerRow(double omega) {
  const double s = std::sin(omega), c = std::cos(omega);
  return {c * c, s * s, 2 * s * c};
}

void requireSameLength(std::size_t a, std::size_t b, const char *what) {
  if (a != b)
    throw InputError("", what,
                     "lengths differ (" + std::to_string(a) + " angles, " + std::to_string(b) + " curvatures)");
}

void requireFinite(std::span<const double> v, const char *what) {
  for (std::size_t i = 0; i < v.size(); ++i)
    if (!std::isfinite(v[i])) throw InputError("", std::string(what) + " " + std::to_string(i), "not finite");
}

/// Directions equal modulo π (within tolerance) are one independent curve.
struct DirectionClass {
  double omega; ///< the first member's angle
  double k;     ///< mean normal curvature: its least-squares value
  int count;
};

std::vector<DirectionClass> groupDirections(std::span<const double> omegas, std::span<const double> ks,
                                            double tolerance) {
  std::vector<DirectionClass> classes;
  for (std::size_t i = 0; i < omegas.size(); ++i) {
    auto same = [&](const DirectionClass &c) { return std::abs(std::sin(omegas[i] - c.omega)) <= tolerance; };
    auto it = std::find_if(classes.begin(), classes.end(), same);
    if (it == classes.end()) {
      classes.push_back({omegas[i], ks[i], 1});
    } else {
      it->k += (ks[i] - it->k) / double(++it->count); // running mean
    }
  }
  return classes;
}

// ---- the cubic of [SV14] App. A -------------------------------------------

/// Real roots of c3 x³ + c2 x² + c1 x + c0 with c3 ≠ 0, each polished by Newton.
std::vector<double> realCubicRoots(double c3, double c2, double c1, double c0) {
  const double A = c2 / c3, B = c1 / c3, C = c0 / c3;
  // Depressed cubic y³ + p y + q, x = y − A/3.
  const double p = B - A * A / 3;
  const double q = 2 * A * A * A / 27 - A * B / 3 + C;
  const double disc = 0.25 * q * q + p * p * p / 27;
  std::vector<double> roots;
  if (disc > 0) {
    // One real root (Cardano), written to avoid cancellation of u and p/(3u).
    const double u = std::cbrt(-0.5 * q - std::copysign(std::sqrt(disc), q));
    const double r = (u != 0 ? u - p / (3 * u) : 0.0) - A / 3;
    roots.push_back(r);
    // Near a double root roundoff can push disc above 0 and hide the pair;
    // keep it (the callers compare candidates, a spurious one is harmless).
    const double hb = 0.5 * (A + r), qc = B + (A + r) * r; // x² + 2hb x + qc
    if (hb * hb - qc >= -1e-12 * std::max({1.0, hb * hb, std::abs(qc)})) roots.push_back(-hb);
  } else {
    // Three real roots (trigonometric form); p ≤ 0 here.
    const double m = 2 * std::sqrt(std::max(0.0, -p / 3));
    const double arg = m > 0 ? std::clamp(3 * q / (p * m), -1.0, 1.0) : 0.0;
    const double theta = std::acos(arg) / 3;
    for (int j = 0; j < 3; ++j) roots.push_back(m * std::cos(theta - 2 * pi * j / 3) - A / 3);
  }
  for (double &x : roots) {
    for (int it = 0; it < 4; ++it) {
      const double f = ((x + A) * x + B) * x + C;
      const double df = (3 * x + 2 * A) * x + B;
      if (df == 0) break;
      const double next = x - f / df;
      const double fnext = ((next + A) * next + B) * next + C;
      if (!(std::abs(fnext) < std::abs(f))) break;
      x = next;
    }
  }
  return roots;
}

/// n = 2 of [SV14] Sec. 2 (i) with k1 ≠ k2 and both non-zero: eqs. (7)–(8) by
/// the cubic of App. A.
CurvatureFit fitTwoDirections(double omega1, double k1, double omega2, double k2) {
  // App. A divides by d = s2²c1² − s1²c2² = sin(ω2 − ω1)·sin(ω1 + ω2), which
  // vanishes whenever ω1 + ω2 ≡ 0 (mod π), e.g. ω = ±30°. The problem is
  // rotation-covariant (ω → ω − θ gives λ → λ − θ, κ1, κ2 unchanged), so we
  // work in the frame where ω1 + ω2 = π/2, i.e. ω1 = π/4 − δ, ω2 = π/4 + δ:
  // there |d| = |sin 2δ| is as large as it can be for these two directions.
  const double theta = 0.5 * (omega1 + omega2) - 0.25 * pi;
  const double S = std::sin(omega2 - omega1), C = std::cos(omega2 - omega1); // sin 2δ, cos 2δ

  // Solve in units of the larger |k| (the cubic's coefficients scale as
  // 1, k, k², k³), then scale back.
  const double scale = std::max(std::abs(k1), std::abs(k2));
  const double m = 0.5 * (k1 + k2) / scale;     // mean of the data
  const double h = 0.5 * (k1 - k2) / scale / S; // half difference / d

  // In this frame s2 = c1, c2 = s1 and d = S, so App. A's line of forms
  // matching both curvatures (eq. 7), W_i = a_i W12 + b_i, has
  //   a1 = a2 = −C,  b1 = m + h,  b2 = m − h,
  // and its cubic coefficients (App. A; we checked them symbolically: they
  // are the numerator of f̂' = num/(W1W2 − W12²)³ for f̂ = (W1² + W2² + 2W12²)/
  // (W1W2 − W12²)²), divided by 4, become
  //   c3 = S²(1 + C²),  c2 = −3S²Cm,  c1 = 3m²S² + h²(1 − 3C²),  c0 = Cm(m² + 3h²).
  // The closed forms matter: App. A's expanded c3 = 2((a1−a2)² − a1a2(a1²+a2²) + 2)
  // = 2(1 − a1a2)(a1² + a2² + 2) cancels catastrophically for close directions.
  // c3 > 0 always: the cubic never drops degree.
  const double c3 = S * S * (1 + C * C);
  const double cc2 = -3 * S * S * C * m;
  const double cc1 = 3 * m * m * S * S + h * h * (1 - 3 * C * C);
  const double c0 = C * m * (m * m + 3 * h * h);
  CURVENET_CHECK(std::isfinite(c3) && c3 > 0 && std::isfinite(c0), "cubic coefficients c3 = " + std::to_string(c3) +
                                                                        ", c0 = " + std::to_string(c0));

  // Admissible stationary points. With k1·k2 > 0 an elliptic interpolant
  // exists (κ1κ2 > 0 on an interval of W12, with f̂ → ∞ at its ends, so a local
  // minimum lies inside); we admit only elliptic roots there: a saddle between
  // two curves bending the same way is what eq. (8) is meant to avoid ("avoid
  // flat areas, equalize the two values"), and the smaller hyperbolic minima
  // that do occur would jump away from the ZeroCurvature limit. With k1·k2 < 0
  // every interpolant is hyperbolic, f̂ has no poles and → 0 at ±∞; we take its
  // maximum, the least curved interpolant (see FitBranch::UnderdeterminedSaddle).
  const bool elliptic = k1 * k2 > 0;
  struct Candidate {
    double w12, gauss, objective;
  };
  std::optional<Candidate> best;
  for (const double t : realCubicRoots(c3, cc2, cc1, c0)) {
    const double W1 = m + h - C * t, W2 = m - h - C * t;
    const double N = W1 * W1 + W2 * W2 + 2 * t * t; // κ1² + κ2²
    // κ1κ2 = W1W2 − t², expanded so that the large terms (≈ 1/S²) cancel
    // analytically rather than in floating point.
    const double D = (m + h) * (m - h) - t * (2 * m * C + S * S * t);
    // A root with κ1κ2 = 0 is a pole of f̂, not a candidate; "zero" means
    // within the rounding error of the sum above. (Not relative to κ1² + κ2²:
    // close directions legitimately give |κ2/κ1| far below ε.)
    const double roundoff = 64 * std::numeric_limits<double>::epsilon() *
                            (std::abs((m + h) * (m - h)) + std::abs(2 * m * C * t) + S * S * t * t);
    if (!(std::abs(D) > roundoff) || (elliptic && D < 0)) continue;
    const double objective = N / (D * D);
    if (!best || (elliptic ? objective < best->objective : objective > best->objective)) best = {t, D, objective};
  }
  CURVENET_CHECK(best.has_value(), "no admissible root of the App. A cubic, k = " + std::to_string(k1) + ", " +
                                       std::to_string(k2));

  // Principal curvatures of [[W1, t], [t, W2]]: the one of larger magnitude
  // from mean ± radius, the other as κ1κ2 / it, so that a small principal
  // curvature next to a large one keeps its relative accuracy.
  const double t = best->w12;
  const double mean = m - C * t, radius = std::hypot(h, t);
  const double large = mean + std::copysign(radius, mean);
  const double small = best->gauss / large;
  // The eigenvector of mean + radius is at ½ atan2(2W12, W1 − W2).
  const double lambdaPlus = 0.5 * std::atan2(t, h) + theta;
  CurvatureFit fit;
  fit.tensor = mean >= 0 ? ordered(scale * large, scale * small, lambdaPlus)
                         : ordered(scale * small, scale * large, lambdaPlus);
  fit.branch = elliptic ? FitBranch::Underdetermined : FitBranch::UnderdeterminedSaddle;
  return fit;
}

// ---- [HPS09] input ---------------------------------------------------------

void requireTangentGaps(std::span<const double> psi) {
  if (psi.size() < 3)
    throw InputError("", "psi", "at least 3 angles needed (each below π, summing to 2π), got " +
                                    std::to_string(psi.size()));
  double sum = 0;
  for (std::size_t i = 0; i < psi.size(); ++i) {
    if (!(psi[i] > 0 && psi[i] < pi))
      throw InputError("", "psi " + std::to_string(i), "angle " + std::to_string(psi[i]) + " not in (0, π)");
    sum += psi[i];
  }
  if (!(std::abs(sum - 2 * pi) <= 1e-8))
    throw InputError("", "psi", "angles sum to " + std::to_string(sum) + ", not 2π");
}

void requireCurvatures(std::span<const double> psi, std::span<const double> kappaN) {
  requireSameLength(psi.size(), kappaN.size(), "psi/kappaN");
  requireTangentGaps(psi);
  requireFinite(kappaN, "kappaN");
}

double maxAbs(std::span<const double> v) {
  double m = 0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

} // namespace

void fillResiduals(CurvatureFit &fit, std::span<const double> omegas, std::span<const double> ks) {
  double sum = 0, worst = 0;
  for (std::size_t i = 0; i < omegas.size(); ++i) {
    const double r = fit.tensor.normalCurvature(omegas[i]) - ks[i];
    sum += r * r;
    worst = std::max(worst, std::abs(r));
  }
  fit.rmsResidual = omegas.empty() ? 0.0 : std::sqrt(sum / double(omegas.size()));
  fit.maxResidual = worst;
}

// ---- representations -------------------------------------------------------

double WeingartenForm::normalCurvature(double omega) const {
  const double s = std::sin(omega), c = std::cos(omega);
  return w1 * c * c + w2 * s * s + 2 * w12 * s * c;
}

double CurvatureTensor::normalCurvature(double omega) const {
  const double s = std::sin(omega - lambda), c = std::cos(omega - lambda);
  return k1 * c * c + k2 * s * s;
}

WeingartenForm CurvatureTensor::toWeingarten() const {
  const double s = std::sin(lambda), c = std::cos(lambda);
  return {k1 * c * c + k2 * s * s, k1 * s * s + k2 * c * c, (k1 - k2) * s * c};
}

CurvatureTensor CurvatureTensor::fromWeingarten(const WeingartenForm &w) {
  // hypot instead of √D avoids overflow/cancellation; equal to √D / 2.
  const double mean = 0.5 * (w.w1 + w.w2);
  const double radius = std::hypot(0.5 * (w.w1 - w.w2), w.w12);
  const double lambda = radius > 0 ? 0.5 * std::atan2(2 * w.w12, w.w1 - w.w2) : 0.0;
  return {mean + radius, mean - radius, wrapLineAngle(lambda)};
}

// ---- [SV14] fits ------------------------------------------------------------

CurvatureFit fitCurvature(std::span<const double> omegas, std::span<const double> ks, const FitOptions &options) {
  requireSameLength(omegas.size(), ks.size(), "omegas/ks");
  if (omegas.empty()) throw InputError("", "omegas", "no directions given");
  requireFinite(omegas, "omegas");
  requireFinite(ks, "ks");

  const std::vector<DirectionClass> dirs = groupDirections(omegas, ks, options.parallelTolerance);
  const int n = int(dirs.size());
  CurvatureFit fit;

  if (n == 1) {
    fit.tensor = {dirs[0].k, dirs[0].k, 0.0};
    fit.branch = FitBranch::SingleDirection;
  } else if (n == 2) {
    const double ka = dirs[0].k, kb = dirs[1].k;
    const double scale = std::max(std::abs(ka), std::abs(kb));
    const double tol = options.exceptionTolerance * scale;
    if (std::abs(ka - kb) <= tol) {
      // Umbilic exception of Sec. 2 (i). Note: for non-orthogonal directions
      // this is not a stationary point of eq. (8); the paper prescribes it.
      const double k = 0.5 * (ka + kb);
      fit.tensor = {k, k, 0.0};
      fit.branch = FitBranch::Umbilic;
    } else if (std::abs(ka) <= tol || std::abs(kb) <= tol) {
      // Zero exception of Sec. 2 (i): zero principal curvature along the
      // flat curve, so the other principal direction is perpendicular to it
      // and Euler's formula (1) at the other curve gives k = κ sin²(Δω).
      const bool aZero = std::abs(ka) <= tol;
      const double omegaZero = aZero ? dirs[0].omega : dirs[1].omega;
      const double omegaOther = aZero ? dirs[1].omega : dirs[0].omega;
      const double kOther = aZero ? kb : ka;
      const double s = std::sin(omegaOther - omegaZero);
      fit.tensor = ordered(kOther / (s * s), 0.0, omegaZero + 0.5 * pi);
      fit.branch = FitBranch::ZeroCurvature;
    } else {
      fit = fitTwoDirections(dirs[0].omega, ka, dirs[1].omega, kb);
    }
  } else if (n == 3) {
    // Sec. 2 (ii): three equations (6) in three unknowns; invertible because
    // no two directions are parallel ([HPS09] Lemma 1).
    Eigen::Matrix3d A;
    Eigen::Vector3d b;
    for (int i = 0; i < 3; ++i) {
      A.row(i) = eulerRow(dirs[i].omega);
      b(i) = dirs[i].k;
    }
    const Eigen::Vector3d w = A.fullPivLu().solve(b);
    fit.tensor = CurvatureTensor::fromWeingarten({w(0), w(1), w(2)});
    fit.branch = FitBranch::Exact;
  } else {
    // Sec. 2 (iii): least squares of eq. (2), linear in (W1, W2, W12). All
    // pairs enter, so parallel duplicates weigh as often as they occur.
    Eigen::MatrixX3d A(omegas.size(), 3);
    Eigen::VectorXd b(omegas.size());
    for (std::size_t i = 0; i < omegas.size(); ++i) {
      A.row(Eigen::Index(i)) = eulerRow(omegas[i]);
      b(Eigen::Index(i)) = ks[i];
    }
    const Eigen::Vector3d w = A.colPivHouseholderQr().solve(b);
    fit.tensor = CurvatureTensor::fromWeingarten({w(0), w(1), w(2)});
    fit.branch = FitBranch::LeastSquares;
  }
  fit.independentDirections = n;
  fillResiduals(fit, omegas, ks);
  return fit;
}

CurvatureFit fitCurvatureConstrained(std::span<const double> omegas, std::span<const double> ks, double omega0,
                                     double k0, const FitOptions &options) {
  requireSameLength(omegas.size(), ks.size(), "omegas/ks");
  requireFinite(omegas, "omegas");
  requireFinite(ks, "ks");
  if (!std::isfinite(omega0)) throw InputError("", "omega0", "not finite");
  if (!std::isfinite(k0)) throw InputError("", "k0", "not finite");

  // The KKT matrix below is regular iff the data fix the form on the plane
  // κ(ω0) = 0, i.e. they hold two directions not parallel to ω0 (then with ω0
  // there are three, and [HPS09] Lemma 1 applies).
  std::vector<double> others;
  for (double w : omegas)
    if (std::abs(std::sin(w - omega0)) > options.parallelTolerance &&
        std::none_of(others.begin(), others.end(), [&](double o) {
          return std::abs(std::sin(w - o)) <= options.parallelTolerance;
        }))
      others.push_back(w);
  if (others.size() < 2)
    throw InputError("", "omegas",
                     "constrained fit needs two data directions not parallel to omega0, got " +
                         std::to_string(others.size()));

  // [SV14] App. A: f = Σ r_i² + Λ (κ(ω0) − k0), r_i = κ(ω_i) − k_i. Its
  // gradient in (W1, W2, W12, Λ), with the W12 equation halved as the paper
  // does, is the system below. The paper prints the constraint row as
  // [c0², s0², s0c0 | 0]; ∂f/∂Λ = 0 is κ(ω0) = k0, whose W12 coefficient is
  // 2 s0 c0 (eq. 6), so that is what we use.
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  Eigen::Vector4d rhs = Eigen::Vector4d::Zero();
  for (std::size_t i = 0; i < omegas.size(); ++i) {
    const Eigen::RowVector3d r = eulerRow(omegas[i]); // [c², s², 2sc]
    // Rows ∂/∂W1, ∂/∂W2: 2 Σ r_i·(c², s²) + Λ (c0², s0²); row ∂/∂W12 / 2.
    const Eigen::Vector3d g(r(0), r(1), 0.5 * r(2));
    M.topLeftCorner<3, 3>() += 2 * g * r;
    rhs.head<3>() += 2 * ks[i] * g;
  }
  const Eigen::RowVector3d a = eulerRow(omega0);
  M.block<3, 1>(0, 3) = Eigen::Vector3d(a(0), a(1), 0.5 * a(2));
  M.block<1, 3>(3, 0) = a;
  rhs(3) = k0;

  const Eigen::FullPivLU<Eigen::Matrix4d> lu(M);
  CURVENET_CHECK(lu.isInvertible(), "Lagrange system singular");
  Eigen::Vector4d x = lu.solve(rhs);
  x += lu.solve(rhs - M * x); // one step of iterative refinement

  CurvatureFit fit;
  fit.tensor = CurvatureTensor::fromWeingarten({x(0), x(1), x(2)});
  fit.branch = FitBranch::Constrained;
  fit.independentDirections = int(groupDirections(omegas, ks, options.parallelTolerance).size());
  fillResiduals(fit, omegas, ks);
  return fit;
}

// ---- [HPS09] ------------------------------------------------------------------

EnclosureResidual enclosureResidual(std::span<const double> psi, std::span<const double> kappaN) {
  requireCurvatures(psi, kappaN);
  const std::size_t n = psi.size();
  EnclosureResidual out;
  if (n % 2 == 1) return out; // Theorem 1: no constraint for odd n.

  // Eq. (6); cot ψ_{i−1} + cot ψ_i = sin(ψ_{i−1} + ψ_i) / (sin ψ_{i−1} sin ψ_i).
  // Array index j is the paper's i = j + 1, hence the sign (−1)^{j+1}.
  double sum = 0;
  for (std::size_t j = 0; j < n; ++j) {
    const double before = psi[(j + n - 1) % n], after = psi[j];
    const double weight = std::sin(before + after) / (std::sin(before) * std::sin(after));
    sum += (j % 2 == 0 ? -1.0 : 1.0) * weight * kappaN[j];
  }
  out.raw = sum;
  const double scale = maxAbs(kappaN);
  out.normalized = scale > 0 ? std::abs(sum) / scale : 0.0;
  return out;
}

EulerResidual eulerResidual(std::span<const double> psi, std::span<const double> kappaN) {
  requireCurvatures(psi, kappaN);
  const std::size_t n = psi.size();

  // Definition 2: φ_1 = 0 along tangent 1, φ_{i+1} = φ_i + ψ_i. Eq. (26) with
  // a free reference direction d is Euler's formula with free λ, i.e. eq. (6)
  // of [SV14], linear in (W1, W2, W12).
  // The third unknown is √2·W12, so that the least-norm solution below is the
  // one of least Frobenius norm of the form (rotation invariant).
  Eigen::MatrixX3d A(n, 3);
  Eigen::VectorXd b(n);
  double phi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    A.row(Eigen::Index(i)) = eulerRow(phi).cwiseProduct(Eigen::RowVector3d(1, 1, invSqrt2));
    b(Eigen::Index(i)) = kappaN[i];
    phi += psi[i];
  }
  // Rank-revealing: an X spans only two directions; the residual is still
  // the unique distance of b from the column space.
  const Eigen::Vector3d w = A.completeOrthogonalDecomposition().solve(b);

  EulerResidual out;
  out.rms = std::sqrt((A * w - b).squaredNorm() / double(n));
  const double scale = maxAbs(kappaN);
  out.normalized = scale > 0 ? out.rms / scale : 0.0;
  out.fit = CurvatureTensor::fromWeingarten({w(0), w(1), invSqrt2 * w(2)});
  return out;
}

bool formsX(std::span<const double> psi, double tolerance) {
  requireTangentGaps(psi);
  if (psi.size() != 4) return false;
  return std::abs(psi[0] + psi[1] - pi) <= tolerance && std::abs(psi[1] + psi[2] - pi) <= tolerance;
}

} // namespace v1
} // namespace curvenet
