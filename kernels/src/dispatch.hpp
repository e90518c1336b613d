// Run-time dispatch shared by the kernel sources (not installed).
#pragma once

#include <cstddef>
#include <cstdint>

namespace curvenet::kernels_impl {

/// The index into a source's Highway dispatch tables for a kernels::Width
/// id (kBestWidth: the CPU's choice; kScalarReference: that target's index,
/// with `reference` set so the kernel runs its width-1 instance).
std::size_t tableIndex(std::int64_t width, bool &reference);

} // namespace curvenet::kernels_impl
