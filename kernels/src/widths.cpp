// The SIMD widths of curvenet/kernels/kernels.hpp (availableWidths,
// bestWidth) and the dispatch-table index every kernel source resolves a
// width through (dispatch.hpp). Compiled once per target (foreach_target)
// for the one per-target function, the vector width.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "widths.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "curvenet/kernels/kernels.hpp"
#include "dispatch.hpp"

HWY_BEFORE_NAMESPACE();
namespace curvenet {
namespace kernels_impl {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

std::size_t Lanes() { return hn::Lanes(hn::ScalableTag<double>()); }

} // namespace HWY_NAMESPACE
} // namespace kernels_impl
} // namespace curvenet
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
#include <hwy/targets.h>

namespace curvenet {
namespace kernels_impl {
HWY_EXPORT(Lanes);

/// Index into the dispatch tables: the best target, the baseline for the
/// scalar reference (its width-1 instance), or the one requested
/// (dispatch.hpp: the other kernel sources dispatch through it too).
std::size_t tableIndex(std::int64_t width, bool &reference) {
  reference = width == kernels::kScalarReference;
  if (width == kernels::kBestWidth || reference) {
    // Resolve the CPU's choice (the first dynamic call initializes it); the
    // reference is that target's width-1 instance.
    (void)HWY_DYNAMIC_DISPATCH(Lanes)();
    return hwy::GetChosenTarget().GetIndex();
  }
  const std::int64_t mask = HWY_CHOSEN_TARGET_SHIFT(width) | HWY_CHOSEN_TARGET_MASK_SCALAR;
  return hwy::Num0BitsBelowLS1Bit_Nonzero64(static_cast<std::uint64_t>(mask & HWY_CHOSEN_TARGET_MASK_TARGETS));
}
} // namespace kernels_impl

inline namespace v1 {
namespace kernels {
using namespace curvenet::kernels_impl;

std::vector<Width> availableWidths() {
  std::vector<Width> widths{{kScalarReference, "scalar", 1}};
  for (std::int64_t target : hwy::SupportedAndGeneratedTargets()) {
    bool reference;
    const std::size_t lanes = HWY_DISPATCH_TABLE(Lanes)[tableIndex(target, reference)]();
    widths.push_back({target, hwy::TargetName(target), lanes});
  }
  return widths;
}

Width bestWidth() {
  bool reference;
  const std::size_t index = tableIndex(kBestWidth, reference);
  for (const Width &w : availableWidths()) {
    bool r;
    if (w.id != kScalarReference && tableIndex(w.id, r) == index) return w;
  }
  return availableWidths().back();
}

} // namespace kernels
} // namespace v1
} // namespace curvenet
#endif
