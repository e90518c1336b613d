// The triangles between two rows of a tessellation (zipRows of
// curvenet/kernels/kernels.hpp). The vector form builds each pair of
// triangles' ids as 64-bit pairs of 32-bit ids and writes them as triples
// (StoreInterleaved3); the scalar reference is the plain loop, which the
// vector form also runs for the rows' ends. Compiled once per target
// (foreach_target), dispatched at run time.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "zip.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

/// The pairs j ∈ [from, to) — (lower[j], lower[j + 1], upper[j]) and
/// (lower[j + 1], upper[j + 1], upper[j]) — at out + 6 j, one at a time.
HWY_INLINE void zipPairs(std::size_t from, std::size_t to, const std::uint32_t *lower, const std::uint32_t *upper,
                         std::uint32_t *out) {
  for (std::size_t j = from; j < to; ++j) {
    std::uint32_t *t = out + 6 * j;
    t[0] = lower[j], t[1] = lower[j + 1], t[2] = upper[j];
    t[3] = lower[j + 1], t[4] = upper[j + 1], t[5] = upper[j];
  }
}

/// zipPairs over [0, pairs), half a vector of pairs at a time: each pair's
/// two triangles are lanes 2q and 2q + 1 of three id vectors, (a, b) built
/// as one 64-bit lane a | b << 32 (on x86, little-endian: a then b). Returns
/// the pairs done.
HWY_INLINE std::size_t zipPairsVector(std::size_t pairs, const std::uint32_t *lower, const std::uint32_t *upper,
                                      std::uint32_t *out) {
#if HWY_TARGET == HWY_SCALAR || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
  (void)pairs, (void)lower, (void)upper, (void)out;
  return 0;
#else
  const hn::ScalableTag<std::uint32_t> d;
  const hn::Repartition<std::uint64_t, decltype(d)> d64;
  const hn::Rebind<std::uint32_t, decltype(d64)> half; // one id per 64-bit lane
  const std::size_t step = hn::Lanes(d64);
  auto pair = [&](const std::uint32_t *first, const std::uint32_t *second) {
    const auto low = hn::PromoteTo(d64, hn::LoadU(half, first));
    const auto high = hn::ShiftLeft<32>(hn::PromoteTo(d64, hn::LoadU(half, second)));
    return hn::BitCast(d, hn::Or(low, high));
  };
  std::size_t j = 0;
  // upper[j + step] is read: j + step < pairs + 1 ≤ upper's length.
  for (; j + step <= pairs; j += step)
    hn::StoreInterleaved3(pair(lower + j, lower + j + 1), pair(lower + j + 1, upper + j + 1),
                          pair(upper + j, upper + j), d, out + 6 * j);
  return j;
#endif
}

void ZipRows(std::size_t m, const std::uint32_t *lower, const std::uint32_t *upper, std::uint32_t *out, bool reference) {
  if (m == 1) {
    out[0] = lower[0], out[1] = lower[1], out[2] = upper[0];
    return;
  }
  // The pairs j < m − 2, then three triangles closing the row.
  const std::size_t pairs = m - 2;
  const std::size_t done = reference ? 0 : zipPairsVector(pairs, lower, upper, out);
  zipPairs(done, pairs, lower, upper, out);
  std::uint32_t *t = out + 6 * pairs;
  t[0] = lower[m - 2], t[1] = lower[m - 1], t[2] = upper[m - 2];
  t[3] = lower[m - 1], t[4] = lower[m], t[5] = upper[m - 2];
  t[6] = lower[m], t[7] = upper[m - 1], t[8] = upper[m - 2];
}

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(ZipRows);
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

void zipRows(std::size_t m, const std::uint32_t *lower, const std::uint32_t *upper, std::uint32_t *triangles,
             std::int64_t width) {
  bool reference;
  const std::size_t index = tableIndex(width, reference);
  HWY_DISPATCH_TABLE(ZipRows)[index](m, lower, upper, triangles, reference);
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
