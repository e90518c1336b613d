// Per-target arithmetic shared by the Gregory kernels (gregory.cpp,
// gregory_jets.cpp): batch inversion and the G² correction patch's rational
// weights. Highway's -inl.h pattern: included once per target through
// foreach_target, hence the toggled guard instead of #pragma once.
#if defined(CURVENET_KERNELS_GREGORY_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef CURVENET_KERNELS_GREGORY_INL_H_
#undef CURVENET_KERNELS_GREGORY_INL_H_
#else
#define CURVENET_KERNELS_GREGORY_INL_H_
#endif

#include <hwy/contrib/math/math-inl.h>
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

/// A G² ribbon's saturated cross parameter r tanh(x / r)
/// (GregorySamples::reach; the caller takes r ≥ 1 as x itself), with
/// d/dx = 1 − tanh² into *slope when given.
template <class D, class V> HWY_INLINE V saturatedCross(D d, V x, double reach, V *slope = nullptr) {
  const V th = hn::Tanh(d, hn::Mul(x, hn::Set(d, 1.0 / reach)));
  if (slope) *slope = hn::NegMulAdd(th, th, hn::Set(d, 1.0));
  return hn::Mul(hn::Set(d, reach), th);
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#endif
