// A tessellation's vertices from jets (jetVertices of
// curvenet/kernels/kernels.hpp): each point with an offset added and its
// unit normal du × dv / |du × dv|, written as interleaved 3-vectors. Written
// once over a Highway descriptor D (CappedTag<double, 1> the width-1 scalar
// reference); compiled once per target (foreach_target), dispatched at run
// time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "vertices.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include "loops-inl.h"

#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

// Argument bundles, shared by every target's instance (defined once).
#ifndef CURVENET_VERTEX_ARGS
#define CURVENET_VERTEX_ARGS
namespace curvenet::kernels_impl {
struct VertexArgs {
  const double *const *jet;
  double offset[3];
  double *points, *normals;
  std::uint32_t *degenerate; ///< their indices, or null
};
} // namespace curvenet::kernels_impl
#endif

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// Samples k … k + lanes − 1: their points and unit normals stored, the
/// indices of their degenerate lanes appended at a.degenerate + found;
/// returns how many there were.
template <class D> HWY_INLINE std::size_t vertexBody(D d, std::size_t k, const VertexArgs &a, std::size_t found) {
  using V = hn::Vec<D>;
  auto load = [&](int column) { return hn::LoadU(d, a.jet[column] + k); };
  hn::StoreInterleaved3(hn::Add(load(0), hn::Set(d, a.offset[0])), hn::Add(load(1), hn::Set(d, a.offset[1])),
                        hn::Add(load(2), hn::Set(d, a.offset[2])), d, a.points + 3 * k);
  const V ax = load(3), ay = load(4), az = load(5), bx = load(6), by = load(7), bz = load(8);
  const V x = hn::Sub(hn::Mul(ay, bz), hn::Mul(az, by));
  const V y = hn::Sub(hn::Mul(az, bx), hn::Mul(ax, bz));
  const V z = hn::Sub(hn::Mul(ax, by), hn::Mul(ay, bx));
  const V size2 = hn::Add(hn::Add(hn::Mul(x, x), hn::Mul(y, y)), hn::Mul(z, z));
  const V a2 = hn::Add(hn::Add(hn::Mul(ax, ax), hn::Mul(ay, ay)), hn::Mul(az, az));
  const V b2 = hn::Add(hn::Add(hn::Mul(bx, bx), hn::Mul(by, by)), hn::Mul(bz, bz));
  const auto flat = hn::Le(size2, hn::Mul(hn::Mul(hn::Set(d, 1e-24), a2), b2));
  const std::size_t degenerate = hn::CountTrue(d, flat);
  if (HWY_UNLIKELY(degenerate > 0) && a.degenerate) {
    std::uint8_t bits[8] = {};
    hn::StoreMaskBits(d, flat, bits);
    for (std::size_t j = 0; j < hn::Lanes(d); ++j)
      if ((bits[j >> 3] >> (j & 7)) & 1) a.degenerate[found++] = static_cast<std::uint32_t>(k + j);
  }
  // One square root and one division a point (the components times the
  // reciprocal length): a division per component kept the divider busy
  // three times as long. A length not above zero (or NaN) gives the zero
  // vector, as normalized() does.
  const V length = hn::Sqrt(size2);
  const auto positive = hn::Gt(length, hn::Zero(d));
  const V inverse = hn::Div(hn::Set(d, 1.0), length);
  hn::StoreInterleaved3(hn::IfThenElseZero(positive, hn::Mul(x, inverse)), hn::IfThenElseZero(positive, hn::Mul(y, inverse)),
                        hn::IfThenElseZero(positive, hn::Mul(z, inverse)), d, a.normals + 3 * k);
  return degenerate;
}

std::size_t JetVertices(std::size_t count, const VertexArgs &args, bool reference) {
  std::size_t degenerate = 0;
  forEachVectorOrReference(reference, count,
                           [&](auto d, std::size_t k) { degenerate += vertexBody(d, k, args, degenerate); });
  return degenerate;
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(JetVertices);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

std::size_t jetVertices(std::size_t count, const double *const jet[9], const double offset[3], double *points,
                        double *normals, std::uint32_t *degenerate, std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  return HWY_DISPATCH_TABLE(JetVertices)[index](
      count, {jet, {offset[0], offset[1], offset[2]}, points, normals, degenerate}, reference);
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
