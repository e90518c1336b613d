// curvenet/vertex_math.hpp — surface curvature at a vertex of a curve network.
//
// Pure functions on plain numbers; no network types. At a vertex the curve
// tangents share one tangent plane. Inside that plane a local x axis is fixed
// and every direction is an angle, in radians, measured counter-clockwise from
// it (seen from the side the surface normal points to). Curvatures are in
// 1/length of the model; a normal curvature is positive when the curve bends
// towards the normal.
//
// Two papers are implemented here, and their equations are cited by number:
//   [SV14] Salvi, Várady: G² surface interpolation over general topology curve
//          networks (CGF 2014), Sec. 2 eqs. (1)–(8) and Appendix A:
//          fitting a surface curvature (κ1, κ2, λ) to the normal curvatures
//          k_i of curves leaving a vertex in directions ω_i.
//   [HPS09] Hermann, Peters, Strotman: A geometric criterion for smooth
//          interpolation of curve networks (SPM 2009): the vertex enclosure
//          constraint (6) for an even number of curves and the Euler curvature
//          constraint (26) it is implied by (Theorem 2).
//
// Angles are only meaningful modulo π for curvature: a curve passing through
// the vertex has the same normal curvature in directions ω and ω + π.
//
// Every function is pure and may be called concurrently from any thread. Bad
// input (mismatched lengths, non-finite values, angles out of range) throws
// InputError (curvenet/error.hpp) naming the offending argument.
#pragma once

#include <span>

namespace curvenet {
inline namespace v1 {

// ---------------------------------------------------------------------------
// Curvature representations
// ---------------------------------------------------------------------------

/// The second fundamental form in the local frame, as the symmetric matrix
/// [[w1, w12], [w12, w2]] ([SV14] eqs. 3–5; the W of [HPS09] eq. 1). Linear in
/// the data, which is why every fit below solves for it first.
struct WeingartenForm {
  double w1 = 0, w2 = 0, w12 = 0;

  /// Normal curvature in direction omega (radians) by [SV14] eq. (6):
  /// w1 cos²ω + w2 sin²ω + 2 w12 sin ω cos ω. Units 1/length.
  double normalCurvature(double omega) const;
};

/// Principal curvatures and direction. Convention: k1 ≥ k2 (k1 is the
/// algebraically larger principal curvature, not the larger in magnitude);
/// lambda is the angle of the k1 principal direction from the local x axis, in
/// radians, reported in (−π/2, π/2] (a principal direction is a line, so λ is
/// defined modulo π). At an umbilic (k1 == k2) λ is arbitrary and reported as 0.
struct CurvatureTensor {
  double k1 = 0, k2 = 0, lambda = 0;

  /// Euler's formula [SV14] eq. (1): κ(ω) = k1 cos²(ω − λ) + k2 sin²(ω − λ).
  /// Holds for any k1, k2 (the convention k1 ≥ k2 is not required here).
  double normalCurvature(double omega) const;

  double gaussianCurvature() const { return k1 * k2; }
  double meanCurvature() const { return 0.5 * (k1 + k2); }

  /// (W1, W2, W12) by [SV14] eqs. (3)–(5).
  WeingartenForm toWeingarten() const;

  /// The inverse of eqs. (3)–(5): the eigen-decomposition of the 2×2 form.
  /// k1,2 = (W1 + W2 ± √D)/2 with D = (W1 − W2)² + 4 W12² as in [SV14] App. A;
  /// λ = ½ atan2(2 W12, W1 − W2), which resolves the sign ambiguity App. A
  /// mentions for its sin²λ formula. Result follows the k1 ≥ k2 convention.
  static CurvatureTensor fromWeingarten(const WeingartenForm &w);
};

// ---------------------------------------------------------------------------
// Curvature fit at a vertex ([SV14] Sec. 2, Appendix A)
// ---------------------------------------------------------------------------

/// Which computation produced a CurvatureFit.
enum class FitBranch {
  /// All data lie along one direction (mod π). [SV14] does not cover this;
  /// we return the umbilic κ1 = κ2 = mean k (a sphere through the curves),
  /// because eq. (8) has no minimizer (it tends to 0 as curvatures grow).
  SingleDirection,
  /// n = 2 and k1 == k2 (within FitOptions::exceptionTolerance): κ1 = κ2 = k,
  /// λ = 0 ([SV14] Sec. 2 (i), first exception).
  Umbilic,
  /// n = 2 and one k is zero: a cylinder-like curvature, zero along that
  /// curve, the other principal curvature from Euler's formula at the other
  /// direction, κ = k / sin²(ω_other − ω_zero) ([SV14] Sec. 2 (i), second
  /// exception). Also taken when both are zero (then it is the plane).
  ZeroCurvature,
  /// n = 2, k1·k2 > 0: the cubic of [SV14] App. A. The result is elliptic
  /// (κ1κ2 > 0) and, among elliptic interpolants, the minimum of
  /// 1/κ1² + 1/κ2² (eq. 8) under the two constraints (eq. 7). Hyperbolic
  /// interpolants are not considered even where eq. (8) has a smaller local
  /// minimum among them: a saddle between two curves bending the same way is
  /// what eq. (8) is meant to prevent, and it would not tend to the
  /// ZeroCurvature result as one k → 0.
  Underdetermined,
  /// n = 2, k1·k2 < 0: every interpolant is hyperbolic and eq. (8) → 0 only
  /// as the curvatures grow without bound, so it has no useful minimum. We
  /// return the stationary point of App. A's cubic where 1/κ1² + 1/κ2² is
  /// largest — its global maximum on the constraint line, the least curved
  /// interpolant — which tends to the ZeroCurvature result as one k → 0.
  UnderdeterminedSaddle,
  /// n = 3: the 3×3 linear system of eq. (6), matched exactly.
  Exact,
  /// n > 3: linear least squares of eq. (2) in (W1, W2, W12).
  LeastSquares,
  /// fitCurvatureConstrained: the Lagrange system of [SV14] App. A.
  Constrained,
};

/// Result of a curvature fit. Residuals are misfits of Euler's formula over
/// *all* input pairs (ω_i, k_i) (parallel duplicates included), in 1/length:
/// rmsResidual = sqrt(Σ (κ(ω_i) − k_i)² / m), maxResidual = max |κ(ω_i) − k_i|,
/// m the number of pairs. For fitCurvatureConstrained they exclude (ω0, k0),
/// which is matched exactly.
struct CurvatureFit {
  CurvatureTensor tensor;
  FitBranch branch = FitBranch::Exact;
  int independentDirections = 0; ///< n of [SV14] Sec. 2: distinct directions mod π
  double rmsResidual = 0;
  double maxResidual = 0;
};

struct FitOptions {
  /// Two directions are the same "independent curve" ([SV14] Fig. 1, e.g.
  /// both legs of an X) when |sin(ω_i − ω_j)| ≤ parallelTolerance. Their k's
  /// are averaged, which is their least-squares value. Dimensionless, ≥ 0.
  double parallelTolerance = 1e-9;
  /// Relative tolerance of the n = 2 exceptions: umbilic when |k1 − k2| ≤ tol·
  /// max|k|, zero curvature when |k_i| ≤ tol·max|k|. Dimensionless, ≥ 0.
  double exceptionTolerance = 1e-12;
};

/// Fits a surface curvature to normal curvatures ks[i] (1/length) of curves
/// leaving the vertex in directions omegas[i] (radians, any real value), per
/// [SV14] Sec. 2, choosing the computation by the number n of independent
/// directions (see FitBranch):
///   n = 1 → SingleDirection;  n = 2 → Umbilic / ZeroCurvature / the cubic;
///   n = 3 → Exact;            n > 3 → LeastSquares.
/// Throws InputError when the spans differ in length, are empty, or hold
/// non-finite values.
CurvatureFit fitCurvature(std::span<const double> omegas, std::span<const double> ks,
                          const FitOptions &options = {});

/// Constrained minimization of [SV14] Sec. 2 (iv) / App. A: minimizes
/// Σ (κ(ω_i) − k_i)² subject to κ(omega0) = k0 exactly, by the Lagrange system
/// of App. A (with the W12 coefficient of its constraint row corrected to
/// 2 s0 c0, see vertex_math.cpp). Used for G² averaging along an edge (Sec. 3.3):
/// omega0 is the edge tangent, k0 its normal curvature.
/// The minimizer is unique only if the data hold at least two directions not
/// parallel to omega0 (by FitOptions::parallelTolerance); otherwise — or on
/// mismatched lengths or non-finite values — throws InputError.
CurvatureFit fitCurvatureConstrained(std::span<const double> omegas, std::span<const double> ks,
                                     double omega0, double k0, const FitOptions &options = {});

// ---------------------------------------------------------------------------
// Vertex enclosure and the Euler constraint ([HPS09])
// ---------------------------------------------------------------------------
//
// Here the curves are numbered around the vertex, and psi[i] is the angle ψ
// from tangent i to tangent i+1 (cyclically; [HPS09] eq. 3, so psi[n−1] is
// from the last tangent back to the first). Requirements, checked with an
// InputError: psi.size() == kappaN.size() ≥ 3, every ψ in (0, π), and
// Σψ = 2π within 1e-8 rad. kappaN[i] is the normal curvature κ_i^n of curve i
// (1/length). Array index i is the paper's index i + 1.

/// The vertex enclosure constraint [HPS09] eq. (6).
struct EnclosureResidual {
  /// Σ_{i=1..n} (−1)^i (cot ψ_{i−1} + cot ψ_i) κ_i^n with the paper's 1-based
  /// signs (ψ_0 = ψ_n), in 1/length; evaluated as sin(ψ_{i−1}+ψ_i) /
  /// (sin ψ_{i−1} sin ψ_i), the form [HPS09] uses in Lemmas 2–4. Exactly 0 for
  /// odd n: there is no constraint (Theorem 1).
  double raw = 0;
  /// |raw| / max_i |κ_i^n|: dimensionless, invariant to the model's scale;
  /// 0 when every κ_i^n is 0. Not bounded by 1: the cot factors grow as a ψ
  /// approaches 0 or π.
  double normalized = 0;
};
EnclosureResidual enclosureResidual(std::span<const double> psi, std::span<const double> kappaN);

/// How far the κ_i^n are from the Euler curvature constraint [HPS09] eq. (26):
/// the least-squares fit of κ1 cos²(φ_i − λ) + κ2 sin²(φ_i − λ) over κ1, κ2,
/// λ, with φ_1 = 0 and φ_{i+1} = φ_i + ψ_i (Definition 2). Defined for every
/// n ≥ 3 (Definition 2 asks for even n; the misfit makes sense regardless).
struct EulerResidual {
  /// sqrt(Σ (κ(φ_i) − κ_i^n)² / n), 1/length. Zero iff (26) holds.
  double rms = 0;
  /// rms / max_i |κ_i^n| (dimensionless, in [0, 1]); 0 when every κ_i^n is 0.
  double normalized = 0;
  /// A best fit, λ measured from tangent 1. When the tangents span fewer than
  /// three directions (an X) the fit is not unique and this is the one of
  /// least Frobenius norm; the residual is unique in every case.
  CurvatureTensor fit;
};
EulerResidual eulerResidual(std::span<const double> psi, std::span<const double> kappaN);

/// Whether the tangents form an X ([HPS09] Lemma 3): n = 4 and opposite
/// tangents collinear, i.e. |ψ1 + ψ2 − π| ≤ tolerance and |ψ2 + ψ3 − π| ≤
/// tolerance (radians). Then (6) holds for any κ_i^n but (26) needs
/// κ1^n = κ3^n and κ2^n = κ4^n. False for n ≠ 4.
bool formsX(std::span<const double> psi, double tolerance = 1e-9);

} // namespace v1
} // namespace curvenet
