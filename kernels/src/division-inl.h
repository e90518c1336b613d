// Quotients without the divider, shared by the kernel sources (Highway's
// -inl.h pattern: included once per target through foreach_target, hence
// the toggled guard instead of #pragma once).
//
// On AVX-512 a vector division keeps the divider busy ~16 cycles (8-lane
// vdivpd on the Intel CPU measured; one 8-lane multiply-add issues every
// half cycle), and a chain of Newton steps, a division each, waits on it.
// The 14-bit reciprocal estimate (vrcp14pd, every width of the target
// through AVX-512VL) refined by Newton's iteration r <- r + r (1 - b r)
// doubles its bits per refinement at two multiply-adds. Every width of the
// AVX-512 target takes the same path, the width-1 reference included, so a
// lane's result does not depend on where it falls in a batch; other targets
// divide. Where a division is one among many independent operations (a
// corner's batch inversion, a blend's normalisation) its latency hides and
// the estimate's extra multiply-adds cost more: face interiors G¹ 4.2-4.4
// against 4.6-4.7 ms with every such quotient estimated (engine_bench
// Evaluate, alternating runs), so only the sweep's Newton steps take it.
#if defined(CURVENET_KERNELS_DIVISION_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef CURVENET_KERNELS_DIVISION_INL_H_
#undef CURVENET_KERNELS_DIVISION_INL_H_
#else
#define CURVENET_KERNELS_DIVISION_INL_H_
#endif

#include <hwy/highway.h>

#include <type_traits>

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
/// 1 / b to 14 bits (vrcp14pd at the vector's width).
template <class V> HWY_INLINE V reciprocalEstimate(V b) {
  using Raw = decltype(b.raw);
  V r;
  if constexpr (std::is_same_v<Raw, __m512d>) r.raw = _mm512_rcp14_pd(b.raw);
  else if constexpr (std::is_same_v<Raw, __m256d>) r.raw = _mm256_rcp14_pd(b.raw);
  else r.raw = _mm_rcp14_pd(b.raw);
  return r;
}
#endif

/// a / b for a Newton step, with `Refinements` refinements of the estimate
/// (one: 28 bits, two: 56). A step from an inexact reciprocal is still a
/// Newton step to first order: the iterate converges as with the exact one
/// and whatever certifies the root tests the root it reaches. Elsewhere than
/// AVX-512 a division.
template <int Refinements, class D, class V = hn::Vec<D>> HWY_INLINE V newtonQuotient(D d, V a, V b) {
#if HWY_ARCH_X86 && HWY_TARGET <= HWY_AVX3
  V r = reciprocalEstimate(b);
  const V one = hn::Set(d, 1.0);
  for (int i = 0; i < Refinements; ++i) r = hn::MulAdd(r, hn::NegMulAdd(b, r, one), r);
  return hn::Mul(a, r);
#else
  (void)d;
  return hn::Div(a, b);
#endif
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#endif
