// Per-target arithmetic shared by the Gregory kernels (gregory.cpp,
// gregory_jets.cpp): batch inversion, the G² correction patch's rational
// weights and the saturated cross parameter. Highway's -inl.h pattern:
// included once per target through foreach_target, hence the toggled guard
// instead of #pragma once.
#if defined(CURVENET_KERNELS_GREGORY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef CURVENET_KERNELS_GREGORY_INL_H_
#undef CURVENET_KERNELS_GREGORY_INL_H_
#else
#define CURVENET_KERNELS_GREGORY_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// In-place reciprocals of m positive values with one division (batch
/// inversion: prefix products, one reciprocal, back substitution). Lanes
/// whose product underflows take m divisions instead.
template <int M, class D, class V> HWY_INLINE void reciprocals(D d, V (&x)[M]) {
  V prefix[M];
  prefix[0] = x[0];
  for (int j = 1; j < M; ++j) prefix[j] = hn::Mul(prefix[j - 1], x[j]);
  if (HWY_UNLIKELY(!hn::AllFalse(d, hn::Not(hn::Gt(prefix[M - 1], hn::Set(d, 1e-250)))))) {
    // Near a corner (or at it, where x = 0 and the caller's factor vanishes).
    const V tiny = hn::Set(d, 1e-300), one = hn::Set(d, 1.0);
    for (int j = 0; j < M; ++j) x[j] = hn::Div(one, hn::Max(x[j], tiny));
    return;
  }
  V inverse = hn::Div(hn::Set(d, 1.0), prefix[M - 1]);
  for (int j = M - 1; j > 0; --j) {
    const V mine = hn::Mul(inverse, prefix[j - 1]);
    inverse = hn::Mul(inverse, x[j]);
    x[j] = mine;
  }
  x[0] = inverse;
}

/// reciprocals for eight values with the products taken as a tree (pairs,
/// quads, all): the same multiplications, but a dependency chain of depth 3
/// on each side of the division instead of 7, so that the corners of a
/// sample overlap in the pipeline.
/// With `numerator`: numerator / x for each (the same operations, the
/// numerator taken into the one division).
template <class D, class V> HWY_INLINE void reciprocals(D d, V (&x)[8], V numerator) {
  const V pair[4] = {hn::Mul(x[0], x[1]), hn::Mul(x[2], x[3]), hn::Mul(x[4], x[5]), hn::Mul(x[6], x[7])};
  const V quad[2] = {hn::Mul(pair[0], pair[1]), hn::Mul(pair[2], pair[3])};
  const V all = hn::Mul(quad[0], quad[1]);
  if (HWY_UNLIKELY(!hn::AllFalse(d, hn::Not(hn::Gt(all, hn::Set(d, 1e-250)))))) {
    const V tiny = hn::Set(d, 1e-300);
    for (V &v : x) v = hn::Div(numerator, hn::Max(v, tiny));
    return;
  }
  const V inverse = hn::Div(numerator, all);
  const V quadInverse[2] = {hn::Mul(inverse, quad[1]), hn::Mul(inverse, quad[0])};
  V pairInverse[4];
  for (int q = 0; q < 2; ++q)
    pairInverse[2 * q] = hn::Mul(quadInverse[q], pair[2 * q + 1]), pairInverse[2 * q + 1] = hn::Mul(quadInverse[q], pair[2 * q]);
  for (int p = 0; p < 4; ++p) {
    const V first = x[2 * p];
    x[2 * p] = hn::Mul(pairInverse[p], x[2 * p + 1]);
    x[2 * p + 1] = hn::Mul(pairInverse[p], first);
  }
}

/// Powers 1, s, s², s³ and 1, t, t², t³, and the reciprocals of the eight
/// denominators s^{3−p} + t^{3−r} of the G² correction patch, (p, r) ≠ (0, 0)
/// row by row.
/// With OverS3, s³ / (s^{3−p} + t^{3−r}) instead of the reciprocals (s³
/// the batch inversion's numerator, at no extra cost).
template <bool OverS3 = false, class D, class V>
HWY_INLINE void g2CornerWeights(D d, V s, V t, V (&sp)[4], V (&tp)[4], V (&den)[8]) {
  const V one = hn::Set(d, 1.0), s2 = hn::Mul(s, s), t2 = hn::Mul(t, t);
  sp[0] = one, sp[1] = s, sp[2] = s2, sp[3] = hn::Mul(s2, s);
  tp[0] = one, tp[1] = t, tp[2] = t2, tp[3] = hn::Mul(t2, t);
  int j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r)
      if (p || r) den[j++] = hn::Add(sp[3 - p], tp[3 - r]);
  reciprocals(d, den, OverS3 ? sp[3] : one);
}

/// gregoryCornerWeights' eight weights s³ t^r / (s^{3−p} + t^{3−r}): they
/// cost what the reciprocals did.
template <class D, class V> HWY_INLINE void g2RationalWeights(D d, V s, V t, V (&w)[8]) {
  V sp[4], tp[4];
  g2CornerWeights<true>(d, s, t, sp, tp, w);
  int j = 0;
  for (int p = 0; p <= 2; ++p)
    for (int r = 0; r <= 2; ++r) {
      if (!p && !r) continue;
      if (r) w[j] = hn::Mul(tp[r], w[j]);
      ++j;
    }
}

/// The two-ribbon blend's weight λ = t^m / (s^m + t^m) of R_{i−1} at a
/// corner (GregorySamples::blendShare; m = 3 for G², 2 for G¹), ½ at the
/// corner itself; with the partials ∂λ/∂s = −m s^{m−1} t^m / (s^m + t^m)²,
/// ∂λ/∂t = m t^{m−1} s^m / (s^m + t^m)² (0 there). "At the corner" is
/// s^m + t^m ≤ 1e-250, where the squared denominator would underflow.
template <int M, class D, class V>
HWY_INLINE V sideBlendWeight(D d, V s, V t, V *bySide = nullptr, V *across = nullptr) {
  static_assert(M == 2 || M == 3);
  const V sLow = M == 3 ? hn::Mul(s, s) : s, tLow = M == 3 ? hn::Mul(t, t) : t; // s^{m−1}, t^{m−1}
  const V sm = hn::Mul(sLow, s), tm = hn::Mul(tLow, t);
  const V sum = hn::Add(sm, tm);
  const auto atCorner = hn::Not(hn::Gt(sum, hn::Set(d, 1e-250)));
  const V inverse = hn::Div(hn::Set(d, 1.0), hn::Max(sum, hn::Set(d, 1e-250)));
  if (bySide) {
    const V m = hn::Set(d, double(M)), inverse2 = hn::Mul(inverse, inverse);
    *bySide = hn::IfThenZeroElse(atCorner, hn::Neg(hn::Mul(hn::Mul(m, hn::Mul(sLow, tm)), inverse2)));
    *across = hn::IfThenZeroElse(atCorner, hn::Mul(hn::Mul(m, hn::Mul(tLow, sm)), inverse2));
  }
  return hn::IfThenElse(atCorner, hn::Set(d, 0.5), hn::Mul(tm, inverse));
}

/// tanh z within a few units in the last place (kernels_test holds it to
/// std::tanh), exactly 0 at 0 and 1 beyond 20 (where tanh rounds to 1),
/// odd, NaN for NaN: tanh |z| = E / (E + 2) with E = e^{2|z|} − 1, from
/// e^f − 1 by its Taylor series on |f| ≤ ln 2 / 2 (13 terms, the rest
/// below 1e-17 relative) and 2^k built from k's bits. Highway's Tanh cost
/// a quarter of a G² patch's face interiors where ribbons saturate (every
/// patch of the real networks tried): its conversions between 64- and
/// 32-bit integers cross lanes, and its range reduction allows any
/// argument where this one needs |z| ≤ 20.
template <class D, class V> HWY_INLINE V tanhOf(D d, V z) {
  const hn::RebindToSigned<D> di;
  const V sign = hn::And(hn::SignBit(d), z);
  const V limit = hn::Set(d, 20.0), a = hn::Xor(z, sign);
  const V clamped = hn::IfThenElse(hn::Gt(a, limit), limit, a), y = hn::Add(clamped, clamped);
  // k = round(y / ln 2) ∈ [0, 58] in the low bits of t (1.5 · 2^52 added:
  // the sum's unit in the last place is 1), f = y − k ln 2 with ln 2 split
  // so that k ln2Hi is exact.
  const V magic = hn::Set(d, 6755399441055744.0);
  const V t = hn::MulAdd(y, hn::Set(d, 1.4426950408889634), magic), k = hn::Sub(t, magic);
  const V f = hn::MulAdd(k, hn::Set(d, -1.90821492927058770002e-10), hn::MulAdd(k, hn::Set(d, -6.93147180369123816490e-01), y));
  // e^f − 1 = f + f² Σ_{n=0}^{11} f^n / (n + 2)!, Estrin's scheme.
  auto c = [&](double factorial) { return hn::Set(d, 1.0 / factorial); };
  const V f2 = hn::Mul(f, f), f4 = hn::Mul(f2, f2), f8 = hn::Mul(f4, f4);
  const V p0 = hn::MulAdd(c(6), f, c(2)), p2 = hn::MulAdd(c(120), f, c(24)), p4 = hn::MulAdd(c(5040), f, c(720));
  const V p6 = hn::MulAdd(c(362880), f, c(40320)), p8 = hn::MulAdd(c(39916800), f, c(3628800));
  const V p10 = hn::MulAdd(c(6227020800.0), f, c(479001600));
  const V low = hn::MulAdd(hn::MulAdd(p6, f2, p4), f4, hn::MulAdd(p2, f2, p0));
  const V high = hn::MulAdd(p10, f2, p8);
  const V q = hn::MulAdd(f2, hn::MulAdd(high, f8, low), f);
  // 2^k from k's bits: (k + 1023) << 52; E = 2^k (q + 1) − 1.
  const auto kBits = hn::Sub(hn::BitCast(di, t), hn::BitCast(di, magic));
  const V scale = hn::BitCast(d, hn::ShiftLeft<52>(hn::Add(kBits, hn::Set(di, 1023))));
  const V E = hn::MulAdd(scale, q, hn::Sub(scale, hn::Set(d, 1.0)));
  return hn::Xor(hn::Div(E, hn::Add(E, hn::Set(d, 2.0))), sign);
}

/// A G² ribbon's saturated cross parameter r tanh(x / r)
/// (GregorySamples::reach; the caller takes r ≥ 1 as x itself), with
/// d/dx = 1 − tanh² into *slope when given.
template <class D, class V> HWY_INLINE V saturatedCross(D d, V x, double reach, V *slope = nullptr) {
  const V th = tanhOf(d, hn::Mul(x, hn::Set(d, 1.0 / reach)));
  if (slope) *slope = hn::NegMulAdd(th, th, hn::Set(d, 1.0));
  return hn::Mul(hn::Set(d, reach), th);
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#endif
