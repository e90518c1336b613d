// Per-target loop helpers shared by the kernel sources (Highway's -inl.h
// pattern: included once per target through foreach_target, hence the
// toggled guard instead of #pragma once).
#if defined(CURVENET_KERNELS_LOOPS_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef CURVENET_KERNELS_LOOPS_INL_H_
#undef CURVENET_KERNELS_LOOPS_INL_H_
#else
#define CURVENET_KERNELS_LOOPS_INL_H_
#endif

#include <hwy/highway.h>

#include <cstddef>

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {

/// Runs body(d, k) over [0, count) in vectors of d's width, the tail at width 1.
template <class D, class Body> HWY_INLINE void forEachVector(D d, std::size_t count, const Body &body) {
  const std::size_t lanes = hwy::HWY_NAMESPACE::Lanes(d);
  std::size_t k = 0;
  for (; k + lanes <= count; k += lanes) body(d, k);
  const hwy::HWY_NAMESPACE::CappedTag<double, 1> one;
  for (; k < count; ++k) body(one, k);
}

/// forEachVector at one lane when `reference` (the scalar reference each
/// kernel keeps beside its SIMD form; kernels_test holds them together) or
/// at the target's full width.
template <class Body> HWY_INLINE void forEachVectorOrReference(bool reference, std::size_t count, const Body &body) {
  if (reference) forEachVector(hwy::HWY_NAMESPACE::CappedTag<double, 1>(), count, body);
  else forEachVector(hwy::HWY_NAMESPACE::ScalableTag<double>(), count, body);
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#endif
