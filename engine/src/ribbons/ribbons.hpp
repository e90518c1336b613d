// Normal fences, linear and parabolic ribbons ([SV14] Sec. 3.2–3.4,
// docs/design.md §3).
//
// A fence belongs to a segment and is shared by the faces on both sides, so
// both patches see the same normal N(u) and their cross-derivatives lie in
// the same plane span(P', N × P'): G¹ by construction. For G² the segment
// also carries one transversal curvature κ_D(u), shared the same way.
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <memory>
#include <span>
#include <vector>

#include "curvenet/network.hpp"

namespace curvenet {
inline namespace v1 {

/// Unit normal along a segment (u ∈ [0, 1]) perpendicular to its tangent,
/// equal to the given vertex normals at both ends: the rotation-minimizing
/// frame by double reflection [WJZL08] from the start normal, with the angle
/// left to the end normal distributed along the arc length.
class NormalFence {
public:
  NormalFence(const BSplineCurve &segment, const Vec3 &startNormal, const Vec3 &endNormal);

  /// Curvature-compatible fence for G² ([SV14] eqs. 13–14, docs/design.md §3):
  /// the rotation-minimizing frame from the start normal, turned about the
  /// tangent by an angle θ(σ) (σ = arc length, L the length) that is the cubic
  /// Hermite with θ(0) = 0, θ(L) = the angle left to the end normal, and
  /// dθ/dσ = startRate, endRate at the ends. The rotation rate about the
  /// tangent is the only component of N' not fixed by N ⊥ P', so the rates
  /// −(S t)·(t × N) of the end vertices' shape operators S give N' = −S(P')
  /// at both ends (Weingarten). Among such angle functions the cubic has the
  /// least ∫ θ''²: the smoothest rotation that still meets the end rates.
  static NormalFence curvatureCompatible(const BSplineCurve &segment, const Vec3 &startNormal,
                                         const Vec3 &endNormal, double startRate, double endRate);

  /// Fence whose normals are taken from a known surface ([SV14] Sec. 5.3):
  /// `normalAt(point)` at the fence samples, projected perpendicular to the
  /// tangent and interpolated. At the two ends the vertex normals (the
  /// curves' common tangent plane, which every patch corner reproduces) win:
  /// where the curves lie only approximately on the surface, the angle
  /// between the field and the vertex normal is taken out linearly along the
  /// segment, so the fence still meets every patch corner exactly (G¹).
  static NormalFence fromNormalField(const BSplineCurve &segment,
                                     const std::function<Vec3(const Vec3 &)> &normalAt, const Vec3 &startNormal,
                                     const Vec3 &endNormal);
  /// The same with the normals given as a function of the segment
  /// parameter u ∈ [0, 1] (normals sampled along the curve, CurveNormals).
  static NormalFence fromNormalsAlong(const BSplineCurve &segment, const std::function<Vec3(double)> &normalAt,
                                      const Vec3 &startNormal, const Vec3 &endNormal);

  Vec3 normal(double u) const;
  /// Normal and its derivative d N / d u.
  void normalAndDerivative(double u, Vec3 &n, Vec3 &dn) const;
  /// The same with the segment's derivatives at u (d^k C / du^k, k = 0..3, as
  /// BSplineCurve::derivatives gives them) supplied by the caller, which has
  /// usually just evaluated the curve: the fence then evaluates only its
  /// normal interpolant. N ⊥ curve[1] holds exactly for the given tangent.
  void normalAndDerivative(double u, const std::array<Vec3, 4> &curve, Vec3 &n, Vec3 &dn) const;
  /// Normal and its first two derivatives with respect to u.
  void normalJet(double u, Vec3 &n, Vec3 &dn, Vec3 &ddn) const;
  /// The same with the segment's derivatives at u supplied (see above).
  void normalJet(double u, const std::array<Vec3, 4> &curve, Vec3 &n, Vec3 &dn, Vec3 &ddn) const;
  /// Segment parameters in (0, 1) where derivatives of the normal may jump:
  /// the knots of the segment and of the normal interpolant.
  std::vector<double> breakpoints() const;
  /// The knots of the normal interpolant alone: where derivatives of the
  /// normal may jump when the caller supplies the curve's derivatives (the
  /// overloads above taking `curve`), whose own knots are then the caller's.
  std::vector<double> interpolantBreakpoints() const;

private:
  NormalFence() = default;
  void build(const BSplineCurve &segment, const Vec3 &startNormal, const Vec3 &endNormal, bool rates,
             double startRate, double endRate);
  BSplineCurve curve_;
  BSplineCurve smoothNormal_; ///< cubic interpolant of the corrected RMF normals (before projection)
};

/// Normal curvature κ_D(u) of the surface along a segment in the common
/// transversal direction D = N × P' (u ∈ [0, 1] the segment parameter), shared
/// by the faces on both sides. With the fence (which fixes the normal and the
/// twist −N'·D) and the curve it fixes the whole second fundamental form along
/// the edge, so parabolic ribbons built from it are G² (Linkage Curve
/// Theorem). A cubic interpolant of samples at u_j = j / (size − 1).
class TransversalCurvature {
public:
  explicit TransversalCurvature(const std::vector<double> &samples);
  /// κ_D and dκ_D/du.
  void valueAndDerivative(double u, double &k, double &dk) const;
  /// Segment parameters in (0, 1) where derivatives of κ_D may jump.
  std::vector<double> breakpoints() const;

private:
  BSplineCurve spline_; ///< κ in the x coordinate
};

/// Side data of a ribbon at one side parameter: P, P', T and T' (d/ds).
struct RibbonJet {
  Vec3 P, dP, T, dT;
};

/// Side data of a parabolic ribbon: also the second cross-derivative C, C'.
struct ParabolicJet {
  Vec3 P, dP, T, dT, C, dC;
};

/// What the nine-term correction patch needs at one end of a side: P, T, C
/// and their first two s-derivatives.
struct SideEndData {
  Vec3 P, dP, ddP, T, dT, ddT, C, dC, ddC;
};

/// Linear ribbon R(s, d) = P(s) + d T(s) of one face side, with
/// T = α D + β P', D = N × P' (eqs. 9, 11, 12) and α, β blended in s, fixed
/// by the end conditions T(0) = −P_prev'(1), T(1) = P_next'(0). At a corner
/// where the loop runs straight on (a T-node seen from the straight side,
/// or the midpoints of a 2-sided face) the neighbour's tangent gives no
/// cross direction; there T = D, the fence direction itself.
class LinearRibbon {
public:
  struct Piece {
    const NormalFence *fence;
    double sFrom, sTo; ///< range of side parameters on this segment
    bool reversed;     ///< the side runs the segment from end to start
    int segment = -1;  ///< network segment index (for edge data lookups)
  };
  LinearRibbon(BSplineCurve curve, std::vector<Piece> pieces);

  /// How α, β run between their end values: linearly, or by the quintic
  /// smoothstep 10s³ − 15s⁴ + 6s⁵, whose first and second derivatives vanish
  /// at both ends. [SV14] leaves α, β free (Sec. 3.2). The G² correction
  /// patch (eq. 22) needs T' and T'' of the two ribbons at a corner to agree
  /// (W₁₁, W₁₂, W₂₁); with linear α, β they differ by the planar turn of T
  /// along each side (in a regular hexagon T'(0) and −T'_prev(1) are √3 edge
  /// lengths apart), and the rational terms turn that mismatch into a
  /// normal offset of the corner interpolants. With the quintic blend both
  /// come from the curve and the fence alone (P'', P''', D', D''), which agree
  /// up to the surface's own variation.
  enum class ScalarBlend { Linear, Quintic };
  /// Sets α, β from the cross-derivative targets at both ends.
  ///
  /// D and P' have the length of the curve's parameter speed |P'(s)|, so
  /// coefficients blended in s alone would make the cross-derivative follow
  /// that speed: on a side whose speed peaks mid-way (a B-spline with uneven
  /// knots or control points) T would grow with it, although how far the
  /// patch reaches across the side has nothing to do with how the curve is
  /// parameterized. With the linear blend (the G¹ schemes) α, β are
  /// therefore blended as the coefficients of the unit frame (D/|D|,
  /// P'/|P'|): T keeps its end targets and its length stays within the
  /// larger of theirs (the blend of two coordinate pairs), whatever the
  /// speed. The quintic blend (gregory-g2) is left as it is: its correction
  /// patch needs T' and T'' of the two ribbons at a corner to agree (see
  /// ScalarBlend), which a speed factor with nonzero slope at the ends
  /// breaks, and a bump-shaped one (flat to second order at both ends) was
  /// measured to double the deviation of `pentagon` (0.10 % → 0.19 %)
  /// without removing the fold it was aimed at.
  void setEndConditions(const Vec3 &startTarget, const Vec3 &endTarget, ScalarBlend blend = ScalarBlend::Linear);

  /// Second derivatives of α, β at one end (quintic blend only; zero by
  /// default). They turn T'' within the tangent plane, where the correction
  /// patch compares it with the neighbouring ribbon's C' (matchCornerTerms);
  /// T stays in the fence's tangent plane, so G¹ and G² across the side are
  /// untouched. Each enters through ½ x² (1 − x)⁵ (x the distance in s from
  /// its end), flat to second order at the far end and small beyond the
  /// first fifth of the side (≤ 0.0055 there), so the ribbon's interior
  /// keeps the quintic blend.
  struct EndCurvature {
    double alpha = 0, beta = 0;
  };
  void setEndCurvatures(const EndCurvature &start, const EndCurvature &end);

  const BSplineCurve &curve() const { return curve_; }
  RibbonJet at(double s) const;
  /// at(s[k]) into out[k] for every k (out.size() ≥ s.size()), bit for bit:
  /// the curve is evaluated once per sample in one batch (sorted parameters
  /// share span searches) and its derivatives are handed to the fence, so
  /// each sample costs one curve and one fence-interpolant evaluation.
  void at(std::span<const double> s, std::span<RibbonJet> out) const;
  /// D = N × P' at the ends (for straight-angle corners).
  Vec3 fenceDirection(double s) const;

  /// Second-order data along the side: P with three s-derivatives, N and T
  /// with two (exact: the curve and the fence's cubic interpolant are
  /// differentiated analytically), and α, β with their slopes.
  struct SecondJet {
    Vec3 P, dP, ddP, dddP, N, dN, ddN, D, dD, T, dT, ddT;
    double alpha, dAlpha, beta, dBeta;
  };
  SecondJet secondJet(double s) const;
  /// secondJet(s) from the ribbon curve's derivatives at s (curve().derivatives(s)).
  SecondJet secondJet(double s, const std::array<Vec3, 4> &curve) const;
  const std::vector<Piece> &pieces() const { return pieces_; }
  /// s moved onto a segment break when within 1e-12 of it. The ribbon's
  /// derivatives jump at a break (each segment has its own fence), so two
  /// evaluations of the same sample whose side parameters differ by a
  /// rounding error (pointwise and through a plan) must land on the same
  /// side of it. Every evaluation path snaps before calling at().
  double snap(double s) const {
    for (size_t j = 0; j + 1 < pieces_.size(); ++j)
      if (std::abs(s - pieces_[j].sTo) <= 1e-12) return pieces_[j].sTo;
    return s;
  }
  /// Index of the piece holding side parameter s, the segment parameter
  /// there, and du/ds.
  int pieceAt(double s, double &local, double &dLocal) const;
  /// Side parameters in (0, 1) where derivatives of P or T may jump: segment
  /// breaks, knots of the side curve, the knots of the fences' normal
  /// interpolants. The jets take the fences' normals with the side curve's
  /// derivatives, so the segments' own knots are not listed: mapped to the
  /// side parameter they land a few ulps off the side curve's knots, and a
  /// breakpoint there would put the table's end samples on the wrong piece.
  std::vector<double> breakpoints() const;

private:
  /// The blend of α, β at s with its first two derivatives.
  std::array<double, 3> profile(double s) const;
  /// α, β and their first two s-derivatives at s (the blend times the speed
  /// scale of setEndConditions) from the ribbon curve's derivatives there.
  struct Coefficients {
    double alpha, dAlpha, ddAlpha, beta, dBeta, ddBeta;
  };
  Coefficients coefficients(double s, const std::array<Vec3, 4> &curve) const;
  void fence(double s, Vec3 &n, Vec3 &dn) const;
  RibbonJet jet(double s, const std::array<Vec3, 4> &curve) const;
  BSplineCurve curve_;
  std::vector<Piece> pieces_;
  /// End values of α, β (linear blend: of the unit frame, see setEndConditions).
  double alpha0_ = 0, alpha1_ = 0, beta0_ = 0, beta1_ = 0;
  std::array<EndCurvature, 2> endCurvatures_{};
  bool hasEndCurvatures_ = false;
  ScalarBlend blend_ = ScalarBlend::Linear;
};

/// Parabolic ribbon R(s, d) = P + d T + ½ d² C ([SV14] eqs. 10, 15) over a
/// linear ribbon: C = κ_T |T|² N, where κ_T |T|² = II(T, T) is the second
/// fundamental form fixed along the edge by the fence (normal N, twist
/// II(P', D) = −N'·D), the curve (II(P', P') = N·P'') and the shared
/// transversal curvature κ_D (II(D, D) = κ_D |D|²):
///   II(T, T) = α² |D|² κ_D − 2αβ N'·D + β² N·P''   for T = αD + βP'.
/// Both faces of an edge thus carry the same second fundamental form, and the
/// curve d ↦ R(s, d) has normal curvature κ_T at d = 0.
class ParabolicRibbon {
public:
  /// `curvatures[j]` belongs to `linear.pieces()[j]` (the same segment).
  ParabolicRibbon(LinearRibbon linear, std::vector<const TransversalCurvature *> curvatures);

  const LinearRibbon &linear() const { return linear_; }
  ParabolicJet at(double s) const;
  /// at(s[k]) into out[k] for every k (out.size() ≥ s.size()), bit for bit,
  /// with the curve evaluated once per sample in one batch (see LinearRibbon::at).
  void at(std::span<const double> s, std::span<ParabolicJet> out) const;
  /// κ_T at s: the normal curvature of the ribbon in the direction of T.
  double crossCurvature(double s) const;
  /// C = II(T, T) N + Γ − (Γ·N) N with Γ = Σ_ends G_end ½ x² (1 − x)³ (x the
  /// distance in s from that end): Γ'' = G at each end, Γ and Γ' zero there
  /// (by default G = 0: C normal). Only C·N enters the surface's curvature
  /// across the side, so this tangential part is free; it changes C'' at
  /// the ends, which the correction patch compares with the neighbouring
  /// ribbon's (W₂₂, matchCornerTerms).
  void setEndTangentialCurvatures(const Vec3 &start, const Vec3 &end);

  /// Correction-patch data at s = 0 and s = 1 (C'' by a fourth-order
  /// one-sided difference of the exact C' with step 1e-3; everything else exact).
  const SideEndData &start() const { return start_; }
  const SideEndData &end() const { return end_; }
  /// P, T, C with two s-derivatives anywhere (for second derivatives of the
  /// patch). C'' is the fourth-order difference of the exact C' (step 1e-3;
  /// one-sided within 4 steps of an end, so that it equals end()/start() there).
  SideEndData secondOrder(double s) const;
  /// Side parameters in (0, 1) where derivatives of P, T or C may jump: the
  /// linear ribbon's and the transversal curvatures' breakpoints.
  std::vector<double> breakpoints() const;

  /// How far along the side (in s, from the end at s = 0 or s = 1) the
  /// second-order Taylor expansion of C at that end stays within
  /// `tolerance` |T| of C itself (½ |ΔC| ≤ tolerance |T(end)|, checked at
  /// twenty steps of 0.05; 1 when it holds over the whole side). The
  /// correction patch extrapolates exactly that expansion (W₂₀ … W₂₂ hold
  /// C, C', C'' of the end) across the face; a curvature bump close to an
  /// end (C'' in the hundreds where C stays below one) makes it reach far
  /// while the ribbon itself does not.
  double cornerTaylorReach(bool atStart, double tolerance) const;

private:
  ParabolicJet jet(double s, const std::array<Vec3, 4> &curve) const;
  LinearRibbon linear_;
  std::vector<const TransversalCurvature *> curvatures_;
  std::array<Vec3, 2> tangentialCurvatures_{};
  bool hasTangential_ = false;
  SideEndData start_, end_;
};

/// Parabolic ribbons over a face's linear ribbons (`linear`, in loop order;
/// `build` makes one over a linear ribbon) whose high-order corner terms
/// agree in the tangent plane.
///
/// The nine-term correction patch (Patch, [SV14] eq. 22) blends at each
/// corner the derivatives ∂_s^p ∂_t^q (p, q ≤ 2) of the two ribbons meeting
/// there, and its rational terms carry their differences into the interior.
/// The normal parts of W₂₁, W₁₂, W₂₂ are fixed by the shared edge data (the
/// fences and transversal curvatures), but their tangential parts are each
/// face's own choice of parameterization. Here T'' of each ribbon takes the
/// other ribbon's C' in the tangent plane (W₂₁ = T_i''(0) against
/// −C_{i−1}'(1), W₁₂ = T_{i−1}''(1) against C_i'(0)) through α'', β''
/// (LinearRibbon::setEndCurvatures, which changes `linear`), and the two C''
/// meet halfway (W₂₂) through the tangential part of C
/// (ParabolicRibbon::setEndTangentialCurvatures).
///
/// What was measured to choose this (gregory-g2, reference deviation max):
/// `pentagon` 0.104 → 0.089 %, `sphere-dodecahedron` 0.312 → 0.271 %,
/// `saddle-nodes` folds 4 → 3, and of the robustness corpus's tangents
/// turned by 1° no face folds (9 did; diagonal ratio 1.090 → 1.033). T''
/// moved only halfway towards C' gives 0.095 %, 0.291 % and 2 folded faces
/// at 1°. Matching every tangential part (also the twists W₁₁ through α',
/// β', C through the neighbouring curve's P'' for W₂₀, W₀₂) leaves one
/// `saddle-nodes` fold but multiplies the deviation of `pentagon` by
/// 3.8–4.6 (any change of the twists does: 0.28 % for half of it, 0.46 %
/// for all) and folds 8 of the 1° corpus faces. None of this unfolds
/// `pocket3sided.lop`, which still folds with every corner term made equal.
/// What folds is the correction patch, not the ribbons: at the worst point
/// of a sphere-dodecahedron face with tangents turned by 3° (corners not
/// blended) the ribbons stay within 0.1–0.8 of their corner (face about 0.7
/// across) while Q reaches 2–4.4, its W₂₂ term alone 1.8–4.3 (C'' = 260–420
/// at corners where |C| < 2: a curvature bump within 5 % of the side's
/// end). The patch therefore also limits how far each ribbon's cross
/// parameter goes by how far its neighbours' corner expansions hold
/// (cornerTaylorReach).
std::vector<ParabolicRibbon> matchCornerTerms(std::vector<LinearRibbon> &linear,
                                              const std::function<ParabolicRibbon(const LinearRibbon &)> &build);

} // namespace v1
} // namespace curvenet
