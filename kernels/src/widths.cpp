// The SIMD widths of curvenet/kernels/kernels.hpp (availableWidths,
// bestWidth) and the dispatch-table index every kernel source resolves a
// width through (dispatch.hpp). Compiled once per target (foreach_target)
// for the one per-target function, the vector width.
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "widths.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep
#include <hwy/highway.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <optional>
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
#if HWY_ARCH_X86 && (defined(__GNUC__) || defined(__clang__))
#include <cpuid.h>
#endif

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

namespace {
/// Whether this CPU runs a 512-bit vector as two 256-bit halves: AMD family
/// 19h is Zen 3 (no AVX-512, so it never reaches the eight-lane path) and
/// Zen 4; Zen 5 (1Ah) has full-width 512-bit units.
bool splitsWideVectors() {
#if HWY_ARCH_X86 && (defined(__GNUC__) || defined(__clang__))
  unsigned eax, ebx, ecx, edx;
  if (!__get_cpuid(0, &eax, &ebx, &ecx, &edx)) return false;
  const bool amd = ebx == 0x68747541 && edx == 0x69746e65 && ecx == 0x444d4163; // "AuthenticAMD"
  if (!amd || !__get_cpuid(1, &eax, &ebx, &ecx, &edx)) return false;
  const unsigned base = (eax >> 8) & 0xf, family = base == 0xf ? base + ((eax >> 20) & 0xff) : base;
  return family == 0x19;
#else
  return false;
#endif
}

/// setEightLaneTables' choice: −1 the CPU's, else 0 or 1.
std::atomic<int> eightLaneOverride{-1};
} // namespace

bool eightLaneTables() {
  static const bool cpuChoice = !splitsWideVectors();
  const int chosen = eightLaneOverride.load(std::memory_order_relaxed);
  return chosen < 0 ? cpuChoice : chosen == 1;
}

void setEightLaneTables(std::optional<bool> eightLanes) {
  eightLaneOverride.store(eightLanes ? int(*eightLanes) : -1, std::memory_order_relaxed);
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
