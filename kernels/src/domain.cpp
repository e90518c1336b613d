// The domain stage of the batched evaluation at arbitrary points
// (sideFrames, cornerBlends of curvenet/kernels/kernels.hpp): every side's
// frame coordinates, then the corner blends and their gradients from the
// distance parameters, a vector of points at a time with all sides in
// registers. Written once over a Highway descriptor D (CappedTag<double, 1>
// the width-1 scalar reference); compiled once per target (foreach_target),
// dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "domain.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "loops-inl.h"

#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

// Argument bundles, shared by every target's instance (defined once).
#ifndef CURVENET_DOMAIN_ARGS
#define CURVENET_DOMAIN_ARGS
namespace curvenet::kernels_impl {
namespace ck = curvenet::kernels;
struct FrameArgs {
  const ck::DomainSides *domain;
  const double *u, *v;
  double *const *x, *const *y;
};

struct BlendArgs {
  const ck::DomainSides *domain;
  int exponent;
  const double *const *y;
  double *const *blend, *const *blendDu, *const *blendDv; ///< the partials null for values alone
};
} // namespace curvenet::kernels_impl
#endif

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace ck = curvenet::kernels;

template <class D> HWY_INLINE void frameBody(D d, std::size_t k, const FrameArgs &a) {
  using V = hn::Vec<D>;
  const ck::DomainSides &f = *a.domain;
  const V u = hn::LoadU(d, a.u + k), v = hn::LoadU(d, a.v + k);
  for (int i = 0; i < f.sides; ++i) {
    const V qx = hn::Sub(u, hn::Set(d, f.px[i])), qy = hn::Sub(v, hn::Set(d, f.py[i]));
    const V ex = hn::Set(d, f.ex[i]), ey = hn::Set(d, f.ey[i]);
    hn::StoreU(hn::Add(hn::Mul(qx, ex), hn::Mul(qy, ey)), d, a.x[i] + k);
    hn::StoreU(hn::Sub(hn::Mul(qy, ex), hn::Mul(qx, ey)), d, a.y[i] + k);
  }
}

void SideFrames(std::size_t count, const FrameArgs &args, bool reference) {
  auto body = [&](auto d, std::size_t k) { frameBody(d, k, args); };
  if (reference) forEachVector(hn::CappedTag<double, 1>(), count, body);
  else forEachVector(hn::ScalableTag<double>(), count, body);
}

/// The blends of one vector of samples; Gradients: with ∂/∂u, ∂/∂v (product
/// and quotient rules through Δ_j^m, whose gradient is m Δ_j^{m−1} ∇Δ_j).
template <bool Gradients, class D> HWY_INLINE void blendBody(D d, std::size_t k, const BlendArgs &a) {
  using V = hn::Vec<D>;
  constexpr int kMax = ck::DomainSides::kMaxSides;
  const ck::DomainSides &f = *a.domain;
  const int n = f.sides;
  const bool cubic = a.exponent == 3;
  V power[kMax], powerU[kMax], powerV[kMax];
  for (int j = 0; j < n; ++j) {
    const V y = hn::LoadU(d, a.y[j] + k), squared = hn::Mul(y, y);
    power[j] = cubic ? hn::Mul(squared, y) : squared;
    if constexpr (Gradients) {
      const V slope = cubic ? hn::Mul(hn::Set(d, 3.0), squared) : hn::Mul(hn::Set(d, 2.0), y);
      powerU[j] = hn::Mul(hn::Neg(slope), hn::Set(d, f.ey[j]));
      powerV[j] = hn::Mul(slope, hn::Set(d, f.ex[j]));
    }
  }
  V b[kMax], bu[kMax], bv[kMax];
  V total = hn::Zero(d), totalU = hn::Zero(d), totalV = hn::Zero(d);
  for (int i = 0; i < n; ++i) {
    const int previous = i == 0 ? n - 1 : i - 1;
    b[i] = hn::Set(d, 1.0), bu[i] = bv[i] = hn::Zero(d);
    for (int j = 0; j < n; ++j) {
      if (j == i || j == previous) continue;
      if constexpr (Gradients) {
        bu[i] = hn::Add(hn::Mul(bu[i], power[j]), hn::Mul(b[i], powerU[j]));
        bv[i] = hn::Add(hn::Mul(bv[i], power[j]), hn::Mul(b[i], powerV[j]));
      }
      b[i] = hn::Mul(b[i], power[j]);
    }
    total = hn::Add(total, b[i]);
    if constexpr (Gradients) totalU = hn::Add(totalU, bu[i]), totalV = hn::Add(totalV, bv[i]);
  }
  const V inverse = hn::Div(hn::Set(d, 1.0), total);
  for (int i = 0; i < n; ++i) {
    if constexpr (Gradients) {
      const V q = hn::Div(b[i], total);
      hn::StoreU(q, d, a.blend[i] + k);
      hn::StoreU(hn::Mul(hn::Sub(bu[i], hn::Mul(q, totalU)), inverse), d, a.blendDu[i] + k);
      hn::StoreU(hn::Mul(hn::Sub(bv[i], hn::Mul(q, totalV)), inverse), d, a.blendDv[i] + k);
    } else {
      hn::StoreU(hn::Mul(b[i], inverse), d, a.blend[i] + k);
    }
  }
}

void CornerBlends(std::size_t count, const BlendArgs &args, bool reference) {
  if (args.blendDu) forEachVectorOrReference(reference, count,
      [&](auto d, std::size_t k) { blendBody<true>(d, k, args); });
  else forEachVectorOrReference(reference, count, [&](auto d, std::size_t k) { blendBody<false>(d, k, args); });
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(SideFrames);
HWY_EXPORT(CornerBlends);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

void sideFrames(std::size_t count, const DomainSides &domain, const double *u, const double *v, double *const *x,
                double *const *y, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(SideFrames)[index](count, {&domain, u, v, x, y}, reference);
}

void cornerBlends(std::size_t count, const DomainSides &domain, int exponent, const double *const *y,
                  double *const *blend, double *const *blendDu, double *const *blendDv, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(CornerBlends)[index](count, {&domain, exponent, y, blend, blendDu, blendDv}, reference);
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
