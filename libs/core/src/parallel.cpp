// Index ranges over a few threads (see parallel.h).
#include "layers/core/parallel.h"

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <thread>
#include <vector>

namespace layers {

void parallel_indices(std::size_t n, int threads, const std::function<void(std::size_t)>& f) {
  std::atomic<std::size_t> next{0};
  std::atomic<bool> stop{false};
  // The failure of the lowest index wins: indices are claimed in order, so
  // every index below it has run, and the error is the one a single thread
  // would have met first.
  std::exception_ptr failure;
  std::size_t failed_at = n;
  std::mutex mutex;
  const auto worker = [&] {
    while (!stop) {
      const std::size_t i = next++;
      if (i >= n) return;
      try {
        f(i);
      } catch (...) {
        const std::lock_guard<std::mutex> lock(mutex);
        if (i < failed_at) {
          failed_at = i;
          failure = std::current_exception();
        }
        stop = true;
      }
    }
  };
  const std::size_t wanted = std::min(static_cast<std::size_t>(std::max(threads, 1)), std::max<std::size_t>(n, 1));
  std::vector<std::thread> pool;
  try {
    for (std::size_t t = 1; t < wanted; ++t) pool.emplace_back(worker);
  } catch (...) {  // no more threads: stop the ones started, then report it
    stop = true;
    for (std::thread& t : pool) t.join();
    throw;
  }
  worker();
  for (std::thread& t : pool) t.join();
  if (failure) std::rethrow_exception(failure);
}

}  // namespace layers
