// curvenet/progress.hpp — progress reports from long parallel calls.
//
// A long call (tessellate, and the renderer of the command-line program)
// takes an optional ProgressCallback. Worker threads count finished work
// into a ProgressCounter; only the thread that made the call runs the
// callback, and at most once per interval, so the callback needs no locking
// of its own and costs nothing measurable however fine the work items are.
// The calling thread takes part in the parallel loop (TBB), so reports keep
// coming while the workers run. The last report is exactly 1.
#pragma once

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <thread>

namespace curvenet {
inline namespace v1 {

/// Receives the finished fraction of a call, in [0, 1], non-decreasing, on
/// the thread that made the call. An exception it throws aborts the call and
/// reaches the caller (the output is then not produced).
using ProgressCallback = std::function<void(double fraction)>;

/// Counts finished work items from any thread and reports the fraction
/// through a ProgressCallback on the constructing thread, throttled to one
/// report per `interval`. Without a callback every member is a no-op.
class ProgressCounter {
public:
  /// `total` work items (0 is treated as 1). The callback must outlive the counter.
  ProgressCounter(const ProgressCallback &callback, std::uint64_t total,
                  std::chrono::milliseconds interval = std::chrono::milliseconds(50))
      : callback_(callback ? &callback : nullptr), total_(total ? total : 1), interval_(interval),
        owner_(std::this_thread::get_id()), last_(std::chrono::steady_clock::now()) {
    if (callback_) (*callback_)(0.0);
  }

  /// Adds `items` finished items. Thread-safe; reports only when called on
  /// the constructing thread and the interval has passed since the last report.
  void advance(std::uint64_t items) {
    if (!callback_) return;
    const std::uint64_t done = done_.fetch_add(items, std::memory_order_relaxed) + items;
    if (std::this_thread::get_id() != owner_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < interval_) return;
    last_ = now; // only the owner touches last_
    (*callback_)(done >= total_ ? 1.0 : double(done) / double(total_));
  }

  /// The final report (fraction 1); call on the constructing thread once the work is done.
  void finish() {
    if (callback_) (*callback_)(1.0);
  }

private:
  const ProgressCallback *callback_;
  std::uint64_t total_;
  std::chrono::milliseconds interval_;
  std::thread::id owner_;
  std::chrono::steady_clock::time_point last_;
  std::atomic<std::uint64_t> done_{0};
};

} // namespace v1
} // namespace curvenet
