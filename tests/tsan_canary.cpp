// The TSan part's own check (built only under -fsanitize=thread): two tasks
// of one parallel::parallelFor write the same variable, and ThreadSanitizer
// must say so. Its test passes only on the report, so a suppression or a
// loop wrapper that blinded TSan to races between tasks turns CI red.
#include <chrono>
#include <cstdio>
#include <thread>

#include "parallel/fork_join.hpp"

int main() {
  long shared = 0;
  curvenet::parallel::withThreads(2, [&] {
    curvenet::parallel::parallelFor(0, 64, [&](int i) {
      std::this_thread::sleep_for(std::chrono::microseconds(200)); // let the threads overlap
      shared += i;                                                  // the race
    });
  });
  std::printf("sum %ld\n", shared);
  return 0;
}
