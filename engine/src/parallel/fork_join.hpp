// Parallel loops that ThreadSanitizer can check.
//
// TBB orders a parallel_for — everything the caller wrote before the loop
// happens before each task, every task before the caller's next statement —
// inside libtbb, with atomics and futexes that TSan does not see (Debian's
// libtbb is not instrumented), while TBB's inline header code, which is
// instrumented, races with itself through those unseen edges. No
// suppression can tell those reports from real ones: every task runs below
// TBB's frames. So under TSan these loops run on plain std::threads, whose
// start and join TSan sees, over the pieces TBB's range splitting gives and
// as many threads as TBB would use (the arena set by withThreads, capped by
// tbb::global_control). Every edge TSan then knows is a real one: a race
// between two tasks, or between a task and the caller, is reported.
// Without TSan the loops are exactly tbb::parallel_for and withThreads is a
// tbb::task_arena.
#pragma once

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#if defined(__SANITIZE_THREAD__)
#define CURVENET_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define CURVENET_TSAN 1
#endif
#endif

#ifdef CURVENET_TSAN
#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>
#endif

namespace curvenet {
inline namespace v1 {
namespace parallel {

#ifdef CURVENET_TSAN
namespace detail {

/// The thread limit withThreads set for this thread's loops (0: none).
inline thread_local int arenaThreads = 0;

inline int loopThreads() {
  const int arena = arenaThreads > 0 ? arenaThreads : tbb::this_task_arena::max_concurrency();
  const auto allowed = tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism);
  return std::max(1, std::min(arena, static_cast<int>(std::min<std::size_t>(allowed, 1024))));
}

/// body(piece) for TBB's pieces of `range` on up to loopThreads() threads;
/// the first exception a piece throws is rethrown on the calling thread.
template <class Range, class Body> void runOnThreads(const Range &range, const Body &body) {
  if (range.empty()) return;
  const int threads = loopThreads();
  std::vector<Range> pieces{range};
  const std::size_t wanted = threads > 1 ? 4 * static_cast<std::size_t>(threads) : 1;
  for (std::size_t k = 0; pieces.size() < wanted && k < pieces.size();) {
    if (!pieces[k].is_divisible()) {
      ++k;
      continue;
    }
    Range second(pieces[k], tbb::split());
    pieces.push_back(second);
  }
  std::atomic<std::size_t> next{0};
  std::exception_ptr failure;
  std::mutex failureLock;
  const int limit = arenaThreads;
  auto work = [&] {
    arenaThreads = limit; // nested loops keep the caller's limit
    for (std::size_t k; (k = next++) < pieces.size();) {
      try {
        body(pieces[k]);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(failureLock);
        if (!failure) failure = std::current_exception();
        next = pieces.size();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads && static_cast<std::size_t>(t) < pieces.size(); ++t) pool.emplace_back(work);
  work();
  for (std::thread &t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

} // namespace detail
#endif

/// tbb::parallel_for(range, body).
template <class Range, class Body> void parallelFor(const Range &range, const Body &body) {
#ifdef CURVENET_TSAN
  detail::runOnThreads(range, body);
#else
  tbb::parallel_for(range, body);
#endif
}

/// tbb::parallel_for(first, last, body): one call per index.
template <class Index, class Body> void parallelFor(Index first, Index last, const Body &body) {
#ifdef CURVENET_TSAN
  if (first >= last) return;
  detail::runOnThreads(tbb::blocked_range<Index>(first, last), [&](const tbb::blocked_range<Index> &piece) {
    for (Index i = piece.begin(); i != piece.end(); ++i) body(i);
  });
#else
  tbb::parallel_for(first, last, body);
#endif
}

/// f() with the parallel loops it runs limited to `threads` threads (0: as
/// many as the machine has): tbb::task_arena(threads).execute(f).
template <class F> void withThreads(int threads, const F &f) {
#ifdef CURVENET_TSAN
  const int previous = detail::arenaThreads;
  detail::arenaThreads = threads > 0 ? threads : 0;
  try {
    f();
  } catch (...) {
    detail::arenaThreads = previous;
    throw;
  }
  detail::arenaThreads = previous;
#else
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute(f);
#endif
}

} // namespace parallel
} // namespace v1
} // namespace curvenet
