// parallel_indices: every index once on any thread count, the first
// exception rethrown after the threads stop.
#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <vector>

#include "layers/core/parallel.h"

namespace layers {
namespace {

TEST(ParallelIndices, EveryIndexOnce) {
  for (int threads : {1, 2, 7}) {
    for (std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{100}}) {
      std::vector<std::atomic<int>> seen(n);
      parallel_indices(n, threads, [&](std::size_t i) { ++seen[i]; });
      for (std::size_t i = 0; i < n; ++i) EXPECT_EQ(seen[i], 1) << "index " << i << ", " << threads << " threads";
    }
  }
}

TEST(ParallelIndices, AFailureStopsNewWorkAndIsRethrown) {
  std::atomic<int> ran{0};
  EXPECT_THROW(parallel_indices(1000, 3,
                                [&](std::size_t i) {
                                  ++ran;
                                  if (i == 5) throw std::runtime_error("index 5 failed");
                                }),
               std::runtime_error);
  EXPECT_LT(ran, 1000);
}

}  // namespace
}  // namespace layers
