// The Gregory formula with its exact first derivatives over the domain
// (gregoryJets of curvenet/kernels/kernels.hpp): product, quotient and chain
// rules through the ribbons and the rational weights in one pass; the G²
// weights with their partials alone (gregoryCornerWeightJets). Written
// once over a Highway descriptor D (CappedTag<double, 1> the width-1 scalar
// reference); compiled once per target (foreach_target), dispatched at run
// time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "gregory_jets.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "gregory-inl.h"
#include "loops-inl.h"

#include <array>
#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

// Argument bundles, shared by every target's instance (defined once).
#ifndef CURVENET_GREGORY_JET_ARGS
#define CURVENET_GREGORY_JET_ARGS
namespace curvenet::kernels_impl {
namespace ck = curvenet::kernels;
struct GregoryJetArgs {
  const ck::GregoryJetSamples *in;
  const ck::GregoryCorner *corners;
  ck::DualVec3Span out;
  const ck::GregoryCornerTerms *terms; ///< per corner, G² only
};

struct CornerWeightJetArgs {
  const double *s, *sPrevious;
  double *weights;
  std::size_t stride;
};
} // namespace curvenet::kernels_impl
#endif

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace ck = curvenet::kernels;

/// A value with its two domain partials, in registers.
template <class V> struct DualV {
  V v, u, w; // value, ∂/∂u, ∂/∂v
};

/// Corner i's parameters: s = s_i and sp = s_{i−1} with their gradients,
/// t = 1 − s_{i−1}, and the cross parameters δ = sc of R_{i−1} and δ = tc
/// of R_i, each saturated at its ribbon's reach (G², GregorySamples::reach;
/// cornerParameters when Saturable) as r tanh(x / r), with their slopes
/// dsc/ds and dtc/dt (1 where the ribbon does not saturate). Q takes the
/// same pair, the blends s and t. (addCornerTerm gathers every gradient by
/// those of s and sp.)
template <class V> struct CornerParameters {
  DualV<V> s, sp;
  V t, sc, tc, scSlope, tcSlope;
};

/// A value and the gradient (g₁, g₂) given in a frame turned by (cos θ,
/// sin θ) = turn (GregoryJetSamples::sideTurn), with the gradient turned
/// into the domain's; as it is for (1, 0).
template <class D, class V = hn::Vec<D>> HWY_INLINE DualV<V> turned(D d, V v, V g1, V g2, const double (&turn)[2]) {
  if (turn[0] == 1 && turn[1] == 0) return {v, g1, g2};
  const V c = hn::Set(d, turn[0]), t = hn::Set(d, turn[1]);
  return {v, hn::MulSub(c, g1, hn::Mul(t, g2)), hn::MulAdd(t, g1, hn::Mul(c, g2))};
}

/// Side i's parameter with its gradient turned into the domain's frame.
template <class D>
HWY_INLINE DualV<hn::Vec<D>> sideParameter(D d, std::size_t k, const ck::GregoryJetSamples &in, int i) {
  return turned(d, hn::LoadU(d, in.values.s[i] + k), hn::LoadU(d, in.sDu[i] + k), hn::LoadU(d, in.sDv[i] + k),
                in.sideTurn[i]);
}

/// Corner i's parameters from its two sides' (sideParameter of i and
/// prev = i − 1).
template <bool Saturable, class D, class V = hn::Vec<D>>
HWY_INLINE CornerParameters<V> cornerParameters(D d, const ck::GregoryJetSamples &in, int i, int prev,
                                                const DualV<V> &side, const DualV<V> &previousSide) {
  CornerParameters<V> p;
  p.s = side, p.sp = previousSide;
  p.t = hn::Sub(hn::Set(d, 1.0), p.sp.v);
  p.sc = p.s.v, p.tc = p.t;
  p.scSlope = p.tcSlope = hn::Set(d, 1.0);
  if constexpr (Saturable) {
    if (in.values.reach[prev] < 1) p.sc = saturatedCross(d, p.sc, in.values.reach[prev], &p.scSlope);
    if (in.values.reach[i] < 1) p.tc = saturatedCross(d, p.tc, in.values.reach[i], &p.tcSlope);
  }
  return p;
}

/// The polynomial part Σ s^p t^r taylor[p][r] of a G² correction patch
/// (GregoryCornerTerms) in Horner form, into q[value, ∂/∂s, ∂/∂t][x, y, z].
template <class D, class V>
HWY_INLINE void g2TaylorJet(D d, V s, V t, const ck::GregoryCornerTerms &terms, V (&q)[3][3]) {
  const V two = hn::Set(d, 2.0);
  for (int c = 0; c < 3; ++c) {
    V h[3], dh[3];
    for (int p = 0; p <= 2; ++p) {
      const V t0 = hn::Set(d, terms.taylor[p][0][c]), t1 = hn::Set(d, terms.taylor[p][1][c]);
      const V t2 = hn::Set(d, terms.taylor[p][2][c]);
      h[p] = hn::MulAdd(t, hn::MulAdd(t, t2, t1), t0);
      dh[p] = hn::MulAdd(hn::Mul(two, t), t2, t1);
    }
    q[0][c] = hn::MulAdd(s, hn::MulAdd(s, h[2], h[1]), h[0]);
    q[1][c] = hn::MulAdd(hn::Mul(two, s), h[2], h[1]);
    q[2][c] = hn::MulAdd(s, hn::MulAdd(s, dh[2], dh[1]), dh[0]);
  }
}

/// The rational weights of a G² correction patch with their partials,
/// ρ_j = N / D with N = s³ t^r and D = s^{3−p} + t^{3−r}, j counting
/// (p, r) ≠ (0, 0) row by row (gregoryCornerWeightJets stores the same
/// numbers). The quotient rule with D's reciprocal in hand,
///   ∂ρ/∂s = (∂N/∂s − ρ ∂D/∂s) / D,  ∂ρ/∂t = (∂N/∂t − ρ ∂D/∂t) / D,
/// takes five operations a weight, the monomials N, ∂N and ∂D shared by
/// the weights of a row or column. Where the difference cancels (p = 0,
/// t^{3−r} ≪ s³) its error stays below 3ε t^r / s in absolute terms, as
/// small as the weight's own rounding.
///
/// At the corner s = t = 0 itself the partials have no limit: callers
/// evaluate it pointwise (Patch::evaluateJets; the denominators' reciprocals
/// are clamped there, and the weights come out 0).
template <class D, class V> HWY_INLINE void g2RationalWeightJets(D d, V s, V t, V (&rho)[8], V (&rhoS)[8], V (&rhoT)[8]) {
  V sp3[4], tp3[4], inv[8];
  g2CornerWeights(d, s, t, sp3, tp3, inv);
  const V three = hn::Set(d, 3.0);
  // N = s³ t^r, ∂N/∂s = 3 s² t^r, ∂N/∂t = r s³ t^{r−1} for r = 0, 1, 2;
  // ∂D/∂s = (3 − p) s^{2−p} for p = 0, 1, 2 and ∂D/∂t = (3 − r) t^{2−r}.
  const V N[3] = {sp3[3], hn::Mul(sp3[3], tp3[1]), hn::Mul(sp3[3], tp3[2])};
  const V threeS2 = hn::Mul(three, sp3[2]);
  const V Ns[3] = {threeS2, hn::Mul(threeS2, tp3[1]), hn::Mul(threeS2, tp3[2])};
  // ∂N/∂t on rows 1 and 2 (0 on row 0); ∂D/∂s on columns 0 and 1 (1 on
  // column 2); −∂D/∂t on row 0 and ∂D/∂t on row 1 (1 on row 2).
  const V Nt1 = sp3[3], Nt2 = hn::Add(N[1], N[1]);
  const V Ds[2] = {threeS2, hn::Add(s, s)};
  const V minusDt0 = hn::Mul(hn::Set(d, -3.0), tp3[2]), Dt1 = hn::Add(t, t);
  int j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (!p && !r) continue;
      const V u = inv[j], w = hn::Mul(N[r], u);
      rho[j] = w;
      rhoS[j] = hn::Mul(p == 2 ? hn::Sub(Ns[r], w) : hn::NegMulAdd(w, Ds[p], Ns[r]), u);
      rhoT[j] = r == 0   ? hn::Mul(hn::Mul(w, minusDt0), u)
                : r == 1 ? hn::Mul(hn::NegMulAdd(w, Dt1, Nt1), u)
                         : hn::Mul(hn::Sub(Nt2, w), u);
      ++j;
    }
}

/// The rational part Σ_j ρ_j rational[j] of a G² correction patch added to
/// q, its weights computed (g2RationalWeightJets) or, given `shared`,
/// loaded: rows j, 8 + j, 16 + j of sample k at shared[row · stride + k].
/// Loaded: `shared` is always given, and the computing path is left out.
template <bool Loaded, class D, class V>
HWY_INLINE void addG2RationalJet(D d, std::size_t k, V s, V t, const ck::GregoryCornerTerms &terms, const double *shared,
                                 std::size_t stride, V (&q)[3][3]) {
  auto add = [&](int j, V rho, V rhoS, V rhoT) {
    for (int c = 0; c < 3; ++c) {
      const V R = hn::Set(d, terms.rational[j][c]);
      q[0][c] = hn::MulAdd(rho, R, q[0][c]);
      q[1][c] = hn::MulAdd(rhoS, R, q[1][c]);
      q[2][c] = hn::MulAdd(rhoT, R, q[2][c]);
    }
  };
  if (Loaded || shared) {
    // Each weight loaded where it is used: loaded all at once, GCC kept
    // the 24 vectors live and spilled them to the stack, to read them back.
    for (int j = 0; j < 8; ++j)
      add(j, hn::LoadU(d, shared + j * stride + k), hn::LoadU(d, shared + (8 + j) * stride + k),
          hn::LoadU(d, shared + (16 + j) * stride + k));
    return;
  }
  if constexpr (!Loaded) {
    V rho[8], rhoS[8], rhoT[8];
    g2RationalWeightJets(d, s, t, rho, rhoS, rhoT);
    for (int j = 0; j < 8; ++j) add(j, rho[j], rhoS[j], rhoT[j]);
  }
}

/// (1 − μ) Q for a G¹ corner with its partials in s and t, into
/// q[value, ∂/∂s, ∂/∂t][x, y, z]: Q = a00 + s W(a10, b10; s, t²) +
/// t W(a01, b01; s², t) + s t W(a11, b11; s, t) with every f and its
/// partials scaled by keep = 1 − μ. Each f W(a, b; x, y), W = wa a +
/// (1 − wa) b, wa = x / (x + y), x = x(s), y = y(t): fs, ft the partials
/// of f, xs = dx/ds, yt = dy/dt, r = 1/(x + y).
template <class D, class V>
HWY_INLINE void g1CorrectionJet(D d, V s, V t, const ck::GregoryCorner &corner, double mu, V (&q)[3][3]) {
  const double(*vec)[3] = corner.v;
  auto add = [&](V f, V fs, V ft, V x, V xs, V y, V yt, V r, int slot) {
    const V wa = hn::Mul(x, r), r2 = hn::Mul(r, r);
    // ∂wa/∂s = xs y r², ∂wa/∂t = −x yt r².
    const V waS = hn::Mul(hn::Mul(xs, y), r2), waT = hn::Mul(hn::Mul(x, yt), r2);
    const V fa = hn::Mul(f, wa);
    const V faS = hn::MulAdd(fs, wa, hn::Mul(f, waS)), faT = hn::MulSub(ft, wa, hn::Mul(f, waT));
    const V fb = hn::Sub(f, fa), fbS = hn::Sub(fs, faS), fbT = hn::Sub(ft, faT);
    for (int c = 0; c < 3; ++c) {
      const V va = hn::Set(d, vec[slot][c]), vb = hn::Set(d, vec[slot + 1][c]);
      q[0][c] = hn::MulAdd(fa, va, hn::MulAdd(fb, vb, q[0][c]));
      q[1][c] = hn::MulAdd(faS, va, hn::MulAdd(fbS, vb, q[1][c]));
      q[2][c] = hn::MulAdd(faT, va, hn::MulAdd(fbT, vb, q[2][c]));
    }
  };
  const V keep = hn::Set(d, 1.0 - mu), zero = hn::Zero(d), one = hn::Set(d, 1.0);
  for (int c = 0; c < 3; ++c) q[0][c] = hn::Mul(keep, hn::Set(d, vec[0][c])), q[1][c] = q[2][c] = zero;
  const V s2 = hn::Mul(s, s), t2 = hn::Mul(t, t), two = hn::Set(d, 2.0);
  V den[3] = {hn::Add(s, t2), hn::Add(s2, t), hn::Add(s, t)};
  reciprocals(d, den);
  // s W(a10, b10; s, t²), t W(a01, b01; s², t), s t W(a11, b11; s, t).
  const V st = hn::Mul(s, t), kt = hn::Mul(keep, t), ks = hn::Mul(keep, s);
  add(ks, keep, zero, s, one, t2, hn::Mul(two, t), den[0], 1);
  add(kt, zero, keep, s2, hn::Mul(two, s), t, one, den[1], 3);
  add(hn::Mul(keep, st), kt, ks, s, one, t, one, den[2], 5);
}

/// Corner i's term I = R_{i−1}(s_{i−1}, sc) + R_i(s, tc) − (1 − μ) Q(sc, tc)
/// (with its blend share μ), R(σ, δ) = P + δ T [+ ½ δ² C], given q: (1 − μ)
/// Q and its partials in sc and tc (q[value, ∂/∂sc, ∂/∂tc][x, y, z]; none
/// when not `corrected`, μ = 1). I's gradient is gathered by the gradients
/// of the corner's two side parameters,
///   ∇I = A ∇s + B ∇s_{i−1},  A = ∂I/∂s,  B = ∂I/∂s_{i−1},
/// (sc = s and tc = t = 1 − s_{i−1} where the ribbons do not saturate; else
/// their slopes enter A and B), then acc += B_i I with the product rule.
/// The chain rule so runs once a coordinate for both ribbons and Q together
/// instead of once for each ribbon's two parameters and once for Q's: 8 %
/// fewer operations a G² corner, 12 % a G¹ one. Saturating: the corner's
/// ribbons may saturate (G² only).
template <bool Parabolic, bool Saturating, class D, class V>
HWY_INLINE void addCornerTerm(D d, std::size_t k, const ck::GregoryJetSamples &in, int i, int prev,
                              const CornerParameters<V> &p, const DualV<V> &blend, const V (&q)[3][3], bool corrected,
                              V (&acc)[3][3]) {
  static_assert(Parabolic || !Saturating, "reaches are G² only");
  const ck::GregorySamples &val = in.values;
  auto load = [&](const double *x) { return hn::LoadU(d, x + k); };
  const double mu = val.blendShare[i];
  const V sc = p.sc, tc = p.tc;
  // The blend share's weights of R_{i−1} and R_i, 1 − μ (1 − λ) and 1 − μ λ
  // with λ(s, t), and the first's partials μ (λ_s ∇s − λ_t ∇s_{i−1}) (the
  // second's are their negatives).
  V previousShare = hn::Set(d, 1.0), ownShare = previousShare, shareS = hn::Zero(d), shareSp = shareS;
  if (mu != 0) {
    V lambdaS, lambdaT;
    const V lambda = sideBlendWeight<Parabolic ? 3 : 2>(d, p.s.v, p.t, &lambdaS, &lambdaT), m = hn::Set(d, mu);
    previousShare = hn::MulAdd(m, lambda, hn::Set(d, 1.0 - mu)), ownShare = hn::NegMulAdd(m, lambda, ownShare);
    shareS = hn::Mul(m, lambdaS), shareSp = hn::Neg(hn::Mul(m, lambdaT));
  }
  V hs2, ht2;
  if constexpr (Parabolic) {
    const V half = hn::Set(d, 0.5);
    hs2 = hn::Mul(half, hn::Mul(sc, sc)), ht2 = hn::Mul(half, hn::Mul(tc, tc));
  }
  // B_i ∇s and B_i ∇s_{i−1}: the blend's value taken into the gradients once.
  const V bsU = hn::Mul(blend.v, p.s.u), bsW = hn::Mul(blend.v, p.s.w);
  const V bspU = hn::Mul(blend.v, p.sp.u), bspW = hn::Mul(blend.v, p.sp.w);
  for (int c = 0; c < 3; ++c) {
    // Each ribbon's value, its slope along σ and across δ.
    V lv = hn::MulAdd(sc, load(val.T[prev][c]), load(val.P[prev][c]));
    V lslope = hn::MulAdd(sc, load(in.dT[prev][c]), load(in.dP[prev][c]));
    V lacross = load(val.T[prev][c]);
    V rv = hn::MulAdd(tc, load(val.T[i][c]), load(val.P[i][c]));
    V rslope = hn::MulAdd(tc, load(in.dT[i][c]), load(in.dP[i][c]));
    V racross = load(val.T[i][c]);
    if constexpr (Parabolic) {
      const V lc = load(val.C[prev][c]), rc = load(val.C[i][c]);
      lv = hn::MulAdd(hs2, lc, lv), rv = hn::MulAdd(ht2, rc, rv);
      lslope = hn::MulAdd(hs2, load(in.dC[prev][c]), lslope), rslope = hn::MulAdd(ht2, load(in.dC[i][c]), rslope);
      lacross = hn::MulAdd(sc, lc, lacross), racross = hn::MulAdd(tc, rc, racross);
    }
    // I's value and its partials: R_{i−1} moves with s through sc (across)
    // and with s_{i−1} along, R_i with s along and with s_{i−1} through tc
    // (across, dtc/ds_{i−1} = −tcSlope); Q with s through sc and with
    // s_{i−1} through tc.
    V v, across = lacross, acrossT = racross; // the parts of ∂/∂sc, ∂/∂tc
    if (mu == 0) {
      v = hn::Add(lv, rv);
    } else {
      v = hn::MulAdd(previousShare, lv, hn::Mul(ownShare, rv));
      across = hn::Mul(previousShare, lacross), acrossT = hn::Mul(ownShare, racross);
    }
    if (corrected) v = hn::Sub(v, q[0][c]), across = hn::Sub(across, q[1][c]), acrossT = hn::Sub(acrossT, q[2][c]);
    V A, B;
    if (mu == 0) {
      if constexpr (Saturating) A = hn::MulAdd(p.scSlope, across, rslope), B = hn::NegMulAdd(p.tcSlope, acrossT, lslope);
      else A = hn::Add(across, rslope), B = hn::Sub(lslope, acrossT);
    } else {
      if constexpr (Saturating) across = hn::Mul(p.scSlope, across), acrossT = hn::Mul(p.tcSlope, acrossT);
      // The shares' partials times R_{i−1} − R_i.
      const V gap = hn::Sub(lv, rv);
      A = hn::MulAdd(ownShare, rslope, hn::MulAdd(shareS, gap, across));
      B = hn::MulAdd(previousShare, lslope, hn::MulSub(shareSp, gap, acrossT));
    }
    acc[0][c] = hn::MulAdd(blend.v, v, acc[0][c]);
    acc[1][c] = hn::MulAdd(blend.u, v, hn::MulAdd(bsU, A, hn::MulAdd(bspU, B, acc[1][c])));
    acc[2][c] = hn::MulAdd(blend.w, v, hn::MulAdd(bsW, A, hn::MulAdd(bspW, B, acc[2][c])));
  }
}

/// A G² corner (addCornerTerm) with its correction's value and partials:
/// the polynomial part, then the rational terms. Saturating: the corner's
/// ribbons may saturate, and its weights are its own; else the weights are
/// given when Loaded (GregoryJetSamples::weightJets) or where weightJets[i]
/// is set.
template <bool Loaded, bool Saturating, class D, class V>
HWY_INLINE void addG2Corner(D d, std::size_t k, const ck::GregoryJetSamples &in, int i, int prev,
                            const CornerParameters<V> &p, const ck::GregoryCornerTerms &terms, const DualV<V> &blend,
                            V (&acc)[3][3]) {
  static_assert(!(Loaded && Saturating), "given weights are of unsaturated corners");
  const double mu = in.values.blendShare[i];
  const bool corrected = mu != 1;
  V q[3][3];
  if (corrected) {
    g2TaylorJet(d, p.sc, p.tc, terms, q);
    addG2RationalJet<Loaded>(d, k, p.sc, p.tc, terms, Saturating ? nullptr : in.weightJets[i], in.weightJetStride,
                             q);
    if (mu != 0) {
      const V keep = hn::Set(d, 1.0 - mu);
      for (auto &row : q)
        for (V &x : row) x = hn::Mul(keep, x);
    }
  }
  addCornerTerm<true, Saturating>(d, k, in, i, prev, p, blend, q, corrected, acc);
}

/// A G¹ corner (addCornerTerm) with its correction (g1CorrectionJet).
template <class D, class V>
HWY_INLINE void addG1Corner(D d, std::size_t k, const ck::GregoryJetSamples &in, int i, int prev,
                            const CornerParameters<V> &p, const ck::GregoryCorner &corner, const DualV<V> &blend,
                            V (&acc)[3][3]) {
  const double mu = in.values.blendShare[i];
  const bool corrected = mu != 1;
  V q[3][3];
  if (corrected) g1CorrectionJet(d, p.s.v, p.t, corner, mu, q);
  addCornerTerm<false, false>(d, k, in, i, prev, p, blend, q, corrected, acc);
}

/// The Gregory formula's jet at samples k … k + lanes − 1:
/// Σ_i B_i I_i with the product rule, I_i = R_{i−1} + R_i − Q_i with corner
/// i's blend share taken from the two-ribbon blend. Loaded: a G² patch
/// whose cross parameters do not saturate and whose corners' weights are
/// all given (GregoryJetSamples::weightJets; the tessellation's rotation
/// groups), an instance of its own as gregoryBody's are: with the branches
/// to saturation and to computed weights in the same code, GCC stored the
/// corner's parameters and its correction's polynomial part to the stack
/// for paths this patch never takes.
template <bool Parabolic, bool Loaded, class D>
HWY_INLINE void gregoryJetBody(D d, std::size_t k, const GregoryJetArgs &a) {
  using V = hn::Vec<D>;
  static_assert(Parabolic || !Loaded, "given weights are G² only");
  const ck::GregoryJetSamples &in = *a.in;
  const int n = in.values.sides;
  V acc[3][3]; // [value, du, dv][x, y, z]
  for (auto &row : acc)
    for (V &x : row) x = hn::Zero(d);
  // Each side's parameter loaded and turned once, for the corners at its
  // two ends.
  DualV<V> previousSide = sideParameter(d, k, in, n - 1);
  for (int i = 0; i < n; ++i) {
    const int prev = i == 0 ? n - 1 : i - 1;
    const DualV<V> side = sideParameter(d, k, in, i);
    const CornerParameters<V> p = cornerParameters<Parabolic && !Loaded>(d, in, i, prev, side, previousSide);
    previousSide = side;
    const DualV<V> blend = turned(d, hn::LoadU(d, in.values.blend[i] + k), hn::LoadU(d, in.blendDu[i] + k),
                                  hn::LoadU(d, in.blendDv[i] + k), in.blendTurn[i]);
    if constexpr (Parabolic) {
      // Corners whose ribbons saturate take the slopes of their cross
      // parameters into A and B, and their own weights.
      if (Loaded || (in.values.reach[prev] >= 1 && in.values.reach[i] >= 1))
        addG2Corner<Loaded, false>(d, k, in, i, prev, p, a.terms[i], blend, acc);
      else if constexpr (!Loaded)
        addG2Corner<false, true>(d, k, in, i, prev, p, a.terms[i], blend, acc);
    } else {
      addG1Corner(d, k, in, i, prev, p, a.corners[i], blend, acc);
    }
  }
  for (int c = 0; c < 3; ++c) {
    hn::StoreU(acc[0][c], d, a.out.v[c] + k);
    hn::StoreU(acc[1][c], d, a.out.du[c] + k);
    hn::StoreU(acc[2][c], d, a.out.dv[c] + k);
  }
}

void GregoryCornerWeightJets(std::size_t count, const CornerWeightJetArgs &a, bool reference) {
  // The output's base and stride in locals: read through `a` after each
  // store (which GCC did not prove leaves them alone), they cost three
  // loads a store.
  double *const weights = a.weights;
  const std::size_t stride = a.stride;
  forEachVectorOrReference(reference, count, [&](auto d, std::size_t k) {
    using V = hn::Vec<decltype(d)>;
    // s and t as cornerParameters takes them, so that the weights are the same numbers.
    const V s = hn::LoadU(d, a.s + k), t = hn::Sub(hn::Set(d, 1.0), hn::LoadU(d, a.sPrevious + k));
    V rho[8], rhoS[8], rhoT[8];
    g2RationalWeightJets(d, s, t, rho, rhoS, rhoT);
    for (int j = 0; j < 8; ++j) {
      hn::StoreU(rho[j], d, weights + j * stride + k);
      hn::StoreU(rhoS[j], d, weights + (8 + j) * stride + k);
      hn::StoreU(rhoT[j], d, weights + (16 + j) * stride + k);
    }
  });
}

void GregoryJets(std::size_t count, const GregoryJetArgs &args, bool reference) {
  const ck::GregoryJetSamples &in = *args.in;
  auto run = [&]<bool Parabolic, bool Loaded>() {
    forEachVectorOrReference(reference, count,
                             [&](auto d, std::size_t k) { gregoryJetBody<Parabolic, Loaded>(d, k, args); });
  };
  bool loaded = in.values.parabolic;
  for (int i = 0; i < in.values.sides; ++i)
    loaded = loaded && in.values.reach[i] >= 1 && (in.weightJets[i] || in.values.blendShare[i] == 1);
  if (loaded) run.template operator()<true, true>();
  else if (in.values.parabolic) run.template operator()<true, false>();
  else run.template operator()<false, false>();
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(GregoryJets);
HWY_EXPORT(GregoryCornerWeightJets);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

void gregoryCornerWeightJets(std::size_t count, const double *s, const double *sPrevious, double *weights,
                             std::size_t stride, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(GregoryCornerWeightJets)[index](count, {s, sPrevious, weights, stride}, reference);
}

void gregoryJets(std::size_t count, const GregoryJetSamples &samples, const GregoryCorner *corners, DualVec3Span out,
                 std::int64_t width, const GregoryCornerTerms *terms) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  std::array<GregoryCornerTerms, GregorySamples::kMaxSides> computed;
  if (samples.values.parabolic && !terms) {
    for (int i = 0; i < samples.values.sides; ++i) computed[i] = gregoryCornerTerms(corners[i]);
    terms = computed.data();
  }
  HWY_DISPATCH_TABLE(GregoryJets)[index](count, {&samples, corners, out, terms}, reference);
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
