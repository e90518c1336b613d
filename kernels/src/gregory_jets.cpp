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

/// Corner i's parameters with their partials: s = s_i, sp = s_{i−1},
/// t = 1 − s_{i−1}, and the cross parameters δ = sc of R_{i−1} and δ = tc
/// of R_i, each saturated at its ribbon's reach (G², GregorySamples::reach;
/// cornerParameters when Saturable) with the chain rule through
/// r tanh(x / r). Q takes the same pair, the blends s and t.
template <class V> struct CornerParameters {
  DualV<V> s, sp, t, sc, tc;
};

/// A value and the gradient (g₁, g₂) given in a frame turned by (cos θ,
/// sin θ) = turn (GregoryJetSamples::sideTurn), with the gradient turned
/// into the domain's; as it is for (1, 0).
template <class D, class V = hn::Vec<D>> HWY_INLINE DualV<V> turned(D d, V v, V g1, V g2, const double (&turn)[2]) {
  if (turn[0] == 1 && turn[1] == 0) return {v, g1, g2};
  const V c = hn::Set(d, turn[0]), t = hn::Set(d, turn[1]);
  return {v, hn::MulSub(c, g1, hn::Mul(t, g2)), hn::MulAdd(t, g1, hn::Mul(c, g2))};
}

template <bool Saturable, class D>
HWY_INLINE CornerParameters<hn::Vec<D>> cornerParameters(D d, std::size_t k, const ck::GregoryJetSamples &in, int i,
                                                         int prev) {
  using V = hn::Vec<D>;
  auto load = [&](const double *p) { return hn::LoadU(d, p + k); };
  CornerParameters<V> p;
  p.s = turned(d, load(in.values.s[i]), load(in.sDu[i]), load(in.sDv[i]), in.sideTurn[i]);
  p.sp = turned(d, load(in.values.s[prev]), load(in.sDu[prev]), load(in.sDv[prev]), in.sideTurn[prev]);
  p.t = {hn::Sub(hn::Set(d, 1.0), p.sp.v), hn::Neg(p.sp.u), hn::Neg(p.sp.w)};
  p.sc = p.s, p.tc = p.t;
  if constexpr (Saturable) {
    auto saturate = [&](DualV<V> &x, double reach) {
      if (reach >= 1) return;
      V slope;
      x.v = saturatedCross(d, x.v, reach, &slope);
      x.u = hn::Mul(slope, x.u), x.w = hn::Mul(slope, x.w);
    };
    saturate(p.sc, in.values.reach[prev]), saturate(p.tc, in.values.reach[i]);
  }
  return p;
}

/// G² blend share μ (GregorySamples::blendShare): the weights 1 − μ (1 − λ)
/// of R_{i−1} and 1 − μ λ of R_i, with their partials ±μ ∂λ; 1 and 1 at μ = 0.
template <class V> struct RibbonShares {
  DualV<V> previous, own;
};

template <bool Parabolic, class D>
HWY_INLINE RibbonShares<hn::Vec<D>> ribbonShares(D d, const CornerParameters<hn::Vec<D>> &p, double mu) {
  using V = hn::Vec<D>;
  const V one = hn::Set(d, 1.0);
  RibbonShares<V> shares{{one, hn::Zero(d), hn::Zero(d)}, {one, hn::Zero(d), hn::Zero(d)}};
  if (mu == 0) return shares;
  V lambdaS, lambdaT;
  const V lambda = sideBlendWeight<Parabolic ? 3 : 2>(d, p.s.v, p.t.v, &lambdaS, &lambdaT), m = hn::Set(d, mu);
  const V lambdaU = hn::MulAdd(lambdaS, p.s.u, hn::Mul(lambdaT, p.t.u));
  const V lambdaW = hn::MulAdd(lambdaS, p.s.w, hn::Mul(lambdaT, p.t.w));
  shares.previous = {hn::MulAdd(m, lambda, hn::Set(d, 1.0 - mu)), hn::Mul(m, lambdaU), hn::Mul(m, lambdaW)};
  shares.own = {hn::NegMulAdd(m, lambda, one), hn::Neg(shares.previous.u), hn::Neg(shares.previous.w)};
  return shares;
}

/// The corner's ribbon terms into term[value, ∂/∂u, ∂/∂v][x, y, z]:
/// R_{i−1}(σ = s_{i−1}, δ = sc) + R_i(σ = s, δ = tc), each weighted by its
/// share when μ ≠ 0; for R(σ, δ): value P + δT [+ ½δ²C],
/// ∂ = σ' (P' + δT' [+ ½δ²C']) + δ' (T [+ δC]).
template <bool Parabolic, class D, class V>
HWY_INLINE void ribbonTerms(D d, std::size_t k, const ck::GregoryJetSamples &in, int i, int prev,
                            const CornerParameters<V> &p, const RibbonShares<V> &shares, double mu, V (&term)[3][3]) {
  const ck::GregorySamples &val = in.values;
  auto load = [&](const double *q) { return hn::LoadU(d, q + k); };
  const V half = hn::Set(d, 0.5);
  const DualV<V> &s = p.s, &sp = p.sp, &sc = p.sc, &tc = p.tc;
  const V hs2 = hn::Mul(half, hn::Mul(sc.v, sc.v)), ht2 = hn::Mul(half, hn::Mul(tc.v, tc.v));
  for (int c = 0; c < 3; ++c) {
    V lv = hn::MulAdd(sc.v, load(val.T[prev][c]), load(val.P[prev][c]));
    V lslope = hn::MulAdd(sc.v, load(in.dT[prev][c]), load(in.dP[prev][c]));
    V lacross = load(val.T[prev][c]);
    V rv = hn::MulAdd(tc.v, load(val.T[i][c]), load(val.P[i][c]));
    V rslope = hn::MulAdd(tc.v, load(in.dT[i][c]), load(in.dP[i][c]));
    V racross = load(val.T[i][c]);
    if constexpr (Parabolic) {
      const V lc = load(val.C[prev][c]), rc = load(val.C[i][c]);
      lv = hn::MulAdd(hs2, lc, lv), rv = hn::MulAdd(ht2, rc, rv);
      lslope = hn::MulAdd(hs2, load(in.dC[prev][c]), lslope), rslope = hn::MulAdd(ht2, load(in.dC[i][c]), rslope);
      lacross = hn::MulAdd(sc.v, lc, lacross), racross = hn::MulAdd(tc.v, rc, racross);
    }
    if (mu != 0) {
      // (1 − μ (1 − λ)) R_{i−1} + (1 − μ λ) R_i with the product rule.
      const DualV<V> &previous = shares.previous, &own = shares.own;
      const V lu = hn::MulAdd(sp.u, lslope, hn::Mul(sc.u, lacross)), lw = hn::MulAdd(sp.w, lslope, hn::Mul(sc.w, lacross));
      const V ru = hn::MulAdd(s.u, rslope, hn::Mul(tc.u, racross)), rw = hn::MulAdd(s.w, rslope, hn::Mul(tc.w, racross));
      const V gap = hn::Sub(lv, rv);
      term[0][c] = hn::MulAdd(previous.v, lv, hn::Mul(own.v, rv));
      term[1][c] = hn::MulAdd(previous.v, lu, hn::MulAdd(own.v, ru, hn::Mul(previous.u, gap)));
      term[2][c] = hn::MulAdd(previous.v, lw, hn::MulAdd(own.v, rw, hn::Mul(previous.w, gap)));
      continue;
    }
    term[0][c] = hn::Add(lv, rv);
    term[1][c] = hn::MulAdd(sp.u, lslope, hn::MulAdd(sc.u, lacross, hn::MulAdd(s.u, rslope, hn::Mul(tc.u, racross))));
    term[2][c] = hn::MulAdd(sp.w, lslope, hn::MulAdd(sc.w, lacross, hn::MulAdd(s.w, rslope, hn::Mul(tc.w, racross))));
  }
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
/// ρ_j = s³ t^r / (s^{3−p} + t^{3−r}) with
///   ∂ρ/∂s = s² t^r (3 t^{3−r} + p s^{3−p}) / den²,
///   ∂ρ/∂t = s³ t^{r−1} (r s^{3−p} + (2r − 3) t^{3−r}) / den²  (r = 0: −3 s³ t² / den²),
/// j counting (p, r) ≠ (0, 0) row by row (gregoryCornerWeightJets stores
/// the same numbers).
template <class D, class V> HWY_INLINE void g2RationalWeightJets(D d, V s, V t, V (&rho)[8], V (&rhoS)[8], V (&rhoT)[8]) {
  V sp3[4], tp3[4], inv[8];
  g2CornerWeights(d, s, t, sp3, tp3, inv);
  // s^2 t^r and s^3 t^r for r = 0, 1, 2, shared by the rows p.
  const V s2t[3] = {sp3[2], hn::Mul(sp3[2], tp3[1]), hn::Mul(sp3[2], tp3[2])};
  const V s3t[3] = {sp3[3], hn::Mul(sp3[3], tp3[1]), hn::Mul(sp3[3], tp3[2])};
  int j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (!p && !r) continue;
      const V x = sp3[3 - p], y = tp3[3 - r], i1 = inv[j], i2 = hn::Mul(i1, i1);
      rho[j] = hn::Mul(s3t[r], i1);
      rhoS[j] = hn::Mul(hn::Mul(s2t[r], hn::MulAdd(hn::Set(d, p), x, hn::Mul(hn::Set(d, 3.0), y))), i2);
      rhoT[j] = r ? hn::Mul(hn::Mul(s3t[r - 1], hn::MulAdd(hn::Set(d, r), x, hn::Mul(hn::Set(d, 2 * r - 3), y))), i2)
                  : hn::Mul(hn::Mul(hn::Set(d, -3.0), hn::Mul(sp3[3], tp3[2])), i2);
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

/// term −= (1 − μ) Q for a G² corner: Q and its partials in s and t, then
/// the chain rule through sc and tc once per corner, not per term.
template <bool Loaded, class D, class V>
HWY_INLINE void subtractG2Correction(D d, std::size_t k, const CornerParameters<V> &p, const ck::GregoryCornerTerms &terms,
                                     double mu, const double *shared, std::size_t stride, V (&term)[3][3]) {
  V q[3][3]; // [value, ∂/∂s, ∂/∂t][x, y, z]
  g2TaylorJet(d, p.sc.v, p.tc.v, terms, q);
  addG2RationalJet<Loaded>(d, k, p.sc.v, p.tc.v, terms, shared, stride, q);
  if (mu != 0) {
    const V keep = hn::Set(d, 1.0 - mu);
    for (auto &row : q)
      for (V &x : row) x = hn::Mul(keep, x);
  }
  for (int c = 0; c < 3; ++c) {
    term[0][c] = hn::Sub(term[0][c], q[0][c]);
    term[1][c] = hn::NegMulAdd(q[1][c], p.sc.u, hn::NegMulAdd(q[2][c], p.tc.u, term[1][c]));
    term[2][c] = hn::NegMulAdd(q[1][c], p.sc.w, hn::NegMulAdd(q[2][c], p.tc.w, term[2][c]));
  }
}

/// term −= (1 − μ) Q for a G¹ corner, Q = a00 + s W(a10, b10; s, t²) +
/// t W(a01, b01; s², t) + s t W(a11, b11; s, t) with every f and its
/// partials scaled by 1 − μ. Each f W(a, b; x, y), W = wa a + (1 − wa) b,
/// wa = x / (x + y), x = x(s), y = y(t): fs, ft the partials of f,
/// xs = dx/ds, yt = dy/dt, r = 1/(x + y).
template <class D, class V>
HWY_INLINE void subtractG1Correction(D d, const CornerParameters<V> &p, const ck::GregoryCorner &corner, double mu,
                                     V (&term)[3][3]) {
  const DualV<V> &s = p.s, &t = p.t;
  const double(*vec)[3] = corner.v;
  auto subtract = [&](V f, V fs, V ft, V x, V xs, V y, V yt, V r, int slot) {
    const V wa = hn::Mul(x, r), r2 = hn::Mul(r, r);
    const V A = hn::Mul(hn::Mul(xs, y), r2), B = hn::Mul(hn::Mul(x, yt), r2);
    const V waU = hn::NegMulAdd(B, t.u, hn::Mul(A, s.u)), waV = hn::NegMulAdd(B, t.w, hn::Mul(A, s.w));
    const V fU = hn::MulAdd(ft, t.u, hn::Mul(fs, s.u)), fV = hn::MulAdd(ft, t.w, hn::Mul(fs, s.w));
    const V fa = hn::Mul(f, wa);
    const V faU = hn::MulAdd(fU, wa, hn::Mul(f, waU)), faV = hn::MulAdd(fV, wa, hn::Mul(f, waV));
    const V fb = hn::Sub(f, fa), fbU = hn::Sub(fU, faU), fbV = hn::Sub(fV, faV);
    for (int c = 0; c < 3; ++c) {
      const V va = hn::Set(d, vec[slot][c]), vb = hn::Set(d, vec[slot + 1][c]);
      term[0][c] = hn::NegMulAdd(fa, va, hn::NegMulAdd(fb, vb, term[0][c]));
      term[1][c] = hn::NegMulAdd(faU, va, hn::NegMulAdd(fbU, vb, term[1][c]));
      term[2][c] = hn::NegMulAdd(faV, va, hn::NegMulAdd(fbV, vb, term[2][c]));
    }
  };
  const V keep = hn::Set(d, 1.0 - mu), zero = hn::Zero(d), one = hn::Set(d, 1.0);
  for (int c = 0; c < 3; ++c) term[0][c] = hn::NegMulAdd(keep, hn::Set(d, vec[0][c]), term[0][c]);
  const V s2 = hn::Mul(s.v, s.v), t2 = hn::Mul(t.v, t.v), two = hn::Set(d, 2.0);
  V den[3] = {hn::Add(s.v, t2), hn::Add(s2, t.v), hn::Add(s.v, t.v)};
  reciprocals(d, den);
  // s W(a10, b10; s, t²), t W(a01, b01; s², t), s t W(a11, b11; s, t).
  const V st = hn::Mul(s.v, t.v), kt = hn::Mul(keep, t.v), ks = hn::Mul(keep, s.v);
  subtract(ks, keep, zero, s.v, one, t2, hn::Mul(two, t.v), den[0], 1);
  subtract(kt, zero, keep, s2, hn::Mul(two, s.v), t.v, one, den[1], 3);
  subtract(hn::Mul(keep, st), kt, ks, s.v, one, t.v, one, den[2], 5);
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
  for (int i = 0; i < n; ++i) {
    const int prev = i == 0 ? n - 1 : i - 1;
    const CornerParameters<V> p = cornerParameters<Parabolic && !Loaded>(d, k, in, i, prev);
    const double mu = in.values.blendShare[i];
    V term[3][3];
    ribbonTerms<Parabolic>(d, k, in, i, prev, p, ribbonShares<Parabolic>(d, p, mu), mu, term);
    if (mu == 1) {
      // The two-ribbon blend alone: no correction patch.
    } else if constexpr (Loaded) {
      subtractG2Correction<true>(d, k, p, a.terms[i], mu, in.weightJets[i], in.weightJetStride, term);
    } else if constexpr (Parabolic) {
      // Shared weights are of the parameters themselves: not at a corner
      // whose cross parameters saturate.
      const bool shared = in.weightJets[i] && in.values.reach[prev] >= 1 && in.values.reach[i] >= 1;
      subtractG2Correction<false>(d, k, p, a.terms[i], mu, shared ? in.weightJets[i] : nullptr, in.weightJetStride,
                                  term);
    } else {
      subtractG1Correction(d, p, a.corners[i], mu, term);
    }
    const DualV<V> blend = turned(d, hn::LoadU(d, in.values.blend[i] + k), hn::LoadU(d, in.blendDu[i] + k),
                                  hn::LoadU(d, in.blendDv[i] + k), in.blendTurn[i]);
    for (int c = 0; c < 3; ++c) {
      acc[0][c] = hn::MulAdd(blend.v, term[0][c], acc[0][c]);
      acc[1][c] = hn::MulAdd(blend.u, term[0][c], hn::MulAdd(blend.v, term[1][c], acc[1][c]));
      acc[2][c] = hn::MulAdd(blend.w, term[0][c], hn::MulAdd(blend.v, term[2][c], acc[2][c]));
    }
  }
  for (int c = 0; c < 3; ++c) {
    hn::StoreU(acc[0][c], d, a.out.v[c] + k);
    hn::StoreU(acc[1][c], d, a.out.du[c] + k);
    hn::StoreU(acc[2][c], d, a.out.dv[c] + k);
  }
}

void GregoryCornerWeightJets(std::size_t count, const CornerWeightJetArgs &a, bool reference) {
  forEachVectorOrReference(reference, count, [&](auto d, std::size_t k) {
    using V = hn::Vec<decltype(d)>;
    // s and t as cornerParameters takes them, so that the weights are the same numbers.
    const V s = hn::LoadU(d, a.s + k), t = hn::Sub(hn::Set(d, 1.0), hn::LoadU(d, a.sPrevious + k));
    V rho[8], rhoS[8], rhoT[8];
    g2RationalWeightJets(d, s, t, rho, rhoS, rhoT);
    for (int j = 0; j < 8; ++j) {
      hn::StoreU(rho[j], d, a.weights + j * a.stride + k);
      hn::StoreU(rhoS[j], d, a.weights + (8 + j) * a.stride + k);
      hn::StoreU(rhoT[j], d, a.weights + (16 + j) * a.stride + k);
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
