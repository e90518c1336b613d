// The Composite Ribbon kernel of curvenet/kernels/kernels.hpp, written once
// over a Highway descriptor D and over the jets flag: the formula runs on
// dual numbers (value and the two domain partials) lane by lane; for points
// alone only the values are stored, and the partials' arithmetic, never
// read, is dropped by the compiler. Compiled once per target
// (foreach_target), dispatched at run time like the other kernel sources.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "composite.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "loops-inl.h"

#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

#ifndef CURVENET_COMPOSITE_ARGS
#define CURVENET_COMPOSITE_ARGS
namespace curvenet::kernels_impl {
struct CompositeArgs {
  const kernels::CompositeSamples *in;
  const kernels::GregoryCorner *left, *right;
  kernels::DualVec3Span out; ///< positions: out.v alone
};
} // namespace curvenet::kernels_impl
#endif

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
namespace ck = curvenet::kernels;

namespace {

/// Dual numbers over the lanes of D: value v, partials u (∂/∂u) and w (∂/∂v).
template <class D> struct Duals {
  using V = hn::Vec<D>;
  struct N {
    V v, u, w;
  };
  struct Point {
    N c[3];
  };
  D d;

  HWY_INLINE N constant(double x) const { return {hn::Set(d, x), hn::Zero(d), hn::Zero(d)}; }
  HWY_INLINE N add(N a, N b) const { return {hn::Add(a.v, b.v), hn::Add(a.u, b.u), hn::Add(a.w, b.w)}; }
  HWY_INLINE N sub(N a, N b) const { return {hn::Sub(a.v, b.v), hn::Sub(a.u, b.u), hn::Sub(a.w, b.w)}; }
  HWY_INLINE N mul(N a, N b) const {
    return {hn::Mul(a.v, b.v), hn::MulAdd(a.u, b.v, hn::Mul(a.v, b.u)), hn::MulAdd(a.w, b.v, hn::Mul(a.v, b.w))};
  }
  HWY_INLINE N div(N a, N b) const {
    const V inverse = hn::Div(hn::Set(d, 1.0), b.v), q = hn::Mul(a.v, inverse);
    return {q, hn::Mul(hn::NegMulAdd(q, b.u, a.u), inverse), hn::Mul(hn::NegMulAdd(q, b.w, a.w), inverse)};
  }
  /// γ(x) = x / (2x + 1), the CR reparameterization of distances.
  HWY_INLINE N gamma(N x) const { return div(x, add(add(x, x), constant(1.0))); }
  /// α0(x) = 2x³ − 3x² + 1.
  HWY_INLINE N hermite0(N x) const {
    return add(mul(mul(x, x), sub(add(x, x), constant(3.0))), constant(1.0));
  }
  HWY_INLINE Point scale(N f, const Point &p) const { return {mul(f, p.c[0]), mul(f, p.c[1]), mul(f, p.c[2])}; }
  HWY_INLINE Point add(const Point &a, const Point &b) const {
    return {add(a.c[0], b.c[0]), add(a.c[1], b.c[1]), add(a.c[2], b.c[2])};
  }
  HWY_INLINE Point sub(const Point &a, const Point &b) const {
    return {sub(a.c[0], b.c[0]), sub(a.c[1], b.c[1]), sub(a.c[2], b.c[2])};
  }

  /// W(a, b; x, y) = b + x / (x + y) (a − b); (a + b) / 2 where x + y = 0.
  HWY_INLINE Point rational(const double *a, const double *b, N x, N y) const {
    const N sum = add(x, y);
    N ratio = div(x, sum);
    const auto corner = hn::Eq(sum.v, hn::Zero(d));
    ratio.v = hn::IfThenElse(corner, hn::Set(d, 0.5), ratio.v);
    ratio.u = hn::IfThenZeroElse(corner, ratio.u), ratio.w = hn::IfThenZeroElse(corner, ratio.w);
    Point p;
    for (int c = 0; c < 3; ++c) {
      const V difference = hn::Set(d, a[c] - b[c]);
      p.c[c] = {hn::MulAdd(ratio.v, difference, hn::Set(d, b[c])), hn::Mul(ratio.u, difference),
                hn::Mul(ratio.w, difference)};
    }
    return p;
  }

  /// Gregory's G¹ correction (GregoryCorner layout a00, a10, b10, a01, b01, a11, b11).
  HWY_INLINE Point correction(const ck::GregoryCorner &corner, N s, N t, N gs, N gt) const {
    const auto &v = corner.v;
    const N s2 = mul(s, s), t2 = mul(t, t);
    Point q = add(add(scale(gs, rational(v[1], v[2], s, t2)), scale(gt, rational(v[3], v[4], s2, t))),
                  scale(mul(gs, gt), rational(v[5], v[6], s, t)));
    for (int c = 0; c < 3; ++c) q.c[c].v = hn::Add(q.c[c].v, hn::Set(d, v[0][c]));
    return q;
  }
};

template <bool Jets, class D> HWY_INLINE void compositeBody(D d, std::size_t k, const CompositeArgs &a) {
  using F = Duals<D>;
  using N = typename F::N;
  using Point = typename F::Point;
  const F f{d};
  const ck::CompositeSamples &in = *a.in;
  auto load = [&](const double *p) { return hn::LoadU(d, p + k); };
  auto dual = [&](const double *const(&p)[3]) -> N {
    if constexpr (Jets) return {load(p[0]), load(p[1]), load(p[2])};
    else return {load(p[0]), hn::Zero(d), hn::Zero(d)};
  };
  Point sum{};
  for (auto &c : sum.c) c = f.constant(0.0);
  for (int i = 0; i < in.sides; ++i) {
    const N s = dual(in.s[i]), dist = dual(in.d[i]), blend = dual(in.blend[i]);
    const N one = f.constant(1.0), sigma = f.sub(one, s);
    const N gs = f.gamma(s), gd = f.gamma(dist), gsigma = f.gamma(sigma);
    // Ribbon r at its parameter x with the distance factor γ: P(x) + γ T(x).
    auto ribbon = [&](int r, N x, N g) {
      Point p;
      for (int c = 0; c < 3; ++c) {
        N P{load(in.P[i][r][c]), hn::Zero(d), hn::Zero(d)}, T{load(in.T[i][r][c]), hn::Zero(d), hn::Zero(d)};
        if constexpr (Jets) {
          const auto dP = load(in.dP[i][r][c]), dT = load(in.dT[i][r][c]);
          P.u = hn::Mul(dP, x.u), P.w = hn::Mul(dP, x.w), T.u = hn::Mul(dT, x.u), T.w = hn::Mul(dT, x.w);
        }
        p.c[c] = f.add(P, f.mul(g, T));
      }
      return p;
    };
    const Point centre = ribbon(0, s, gd);                      // R_i(s, d)
    const Point leftRibbon = ribbon(1, f.sub(one, dist), gs);   // R_{i−1}(1 − d, s)
    const Point rightRibbon = ribbon(2, dist, gsigma);          // R_{i+1}(d, 1 − s)
    const Point leftCorrection = f.correction(a.left[i], s, dist, gs, gd);
    const Point rightCorrection = f.correction(a.right[i], sigma, dist, gsigma, gd);
    const N a0s = f.hermite0(s), a1s = f.sub(one, a0s), a0d = f.hermite0(dist);
    const Point curved =
        f.sub(f.sub(f.add(f.add(f.scale(a0s, leftRibbon), f.scale(a0d, centre)), f.scale(a1s, rightRibbon)),
                    f.scale(f.mul(a0s, a0d), leftCorrection)),
              f.scale(f.mul(a1s, a0d), rightCorrection));
    // Lanes whose blend is zero with its partials skip the side, as the
    // scalar formula does: their curved ribbon may not be finite.
    auto zero = hn::Eq(blend.v, hn::Zero(d));
    if constexpr (Jets) zero = hn::And(zero, hn::And(hn::Eq(blend.u, hn::Zero(d)), hn::Eq(blend.w, hn::Zero(d))));
    const Point weighted = f.scale(blend, curved);
    for (int c = 0; c < 3; ++c) {
      sum.c[c].v = hn::Add(sum.c[c].v, hn::IfThenZeroElse(zero, weighted.c[c].v));
      sum.c[c].u = hn::Add(sum.c[c].u, hn::IfThenZeroElse(zero, weighted.c[c].u));
      sum.c[c].w = hn::Add(sum.c[c].w, hn::IfThenZeroElse(zero, weighted.c[c].w));
    }
  }
  const auto half = hn::Set(d, 0.5);
  for (int c = 0; c < 3; ++c) {
    hn::StoreU(hn::Mul(half, sum.c[c].v), d, a.out.v[c] + k);
    if constexpr (Jets) {
      hn::StoreU(hn::Mul(half, sum.c[c].u), d, a.out.du[c] + k);
      hn::StoreU(hn::Mul(half, sum.c[c].w), d, a.out.dv[c] + k);
    }
  }
}

} // namespace

void CompositeRibbon(std::size_t count, const CompositeArgs &args, bool jets, bool reference) {
  if (jets) forEachVectorOrReference(reference, count, [&](auto d, std::size_t k) { compositeBody<true>(d, k, args); });
  else forEachVectorOrReference(reference, count, [&](auto d, std::size_t k) { compositeBody<false>(d, k, args); });
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(CompositeRibbon);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

void compositeRibbonPositions(std::size_t count, const CompositeSamples &samples, const GregoryCorner *left,
                              const GregoryCorner *right, double *const out[3], std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  DualVec3Span span{};
  for (int c = 0; c < 3; ++c) span.v[c] = out[c];
  HWY_DISPATCH_TABLE(CompositeRibbon)[index](count, {&samples, left, right, span}, false, reference);
}

void compositeRibbonJets(std::size_t count, const CompositeSamples &samples, const GregoryCorner *left,
                         const GregoryCorner *right, DualVec3Span out, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(CompositeRibbon)[index](count, {&samples, left, right, out}, true, reference);
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
