// Parallel loops whose fork and join ThreadSanitizer can see.
//
// TBB orders a parallel_for: everything the caller wrote before the loop
// happens before each task, and every task happens before the caller's next
// statement. It does so inside libtbb, with atomics and futexes that TSan
// does not see (Debian's libtbb is not instrumented), so every result a task
// writes and the caller reads would be reported as a race. These wrappers
// state the two edges with TSan's annotations — one token for the fork
// (caller → tasks), another for the join (tasks → caller) — and nothing
// between tasks, so a real race between two tasks is still reported.
// Without TSan the annotations compile to nothing and the wrappers are
// exactly tbb::parallel_for.
#pragma once

#include <tbb/parallel_for.h>

#if defined(__SANITIZE_THREAD__)
#define CURVENET_TSAN 1
#elif defined(__has_feature)
#if __has_feature(thread_sanitizer)
#define CURVENET_TSAN 1
#endif
#endif

#ifdef CURVENET_TSAN
#include <sanitizer/tsan_interface.h>
#endif

namespace curvenet {
inline namespace v1 {
namespace parallel {

/// The happens-before edges of one fork/join. Create it on the calling
/// thread just before handing work to TBB (this is the fork); call
/// taskBegins()/taskEnds() first and last in each task, and joined() on the
/// calling thread once TBB has returned.
class ForkJoin {
public:
  ForkJoin() { release(&fork_); }
  ForkJoin(const ForkJoin &) = delete;
  ForkJoin &operator=(const ForkJoin &) = delete;
  void taskBegins() const { acquire(&fork_); }
  void taskEnds() const { release(&join_); }
  void joined() const { acquire(&join_); }

private:
#ifdef CURVENET_TSAN
  static void release(const char *token) { __tsan_release(const_cast<char *>(token)); }
  static void acquire(const char *token) { __tsan_acquire(const_cast<char *>(token)); }
#else
  static void release(const char *) {}
  static void acquire(const char *) {}
#endif
  char fork_ = 0, join_ = 0; // only their addresses matter
};

/// tbb::parallel_for(range, body) with its fork and join visible to TSan.
template <class Range, class Body> void parallelFor(const Range &range, const Body &body) {
  const ForkJoin edges;
  tbb::parallel_for(range, [&](const Range &part) {
    edges.taskBegins();
    body(part);
    edges.taskEnds();
  });
  edges.joined();
}

/// tbb::parallel_for(first, last, body) (one call per index) with its fork and join visible to TSan.
template <class Index, class Body> void parallelFor(Index first, Index last, const Body &body) {
  const ForkJoin edges;
  tbb::parallel_for(first, last, [&](Index i) {
    edges.taskBegins();
    body(i);
    edges.taskEnds();
  });
  edges.joined();
}

} // namespace parallel
} // namespace v1
} // namespace curvenet
