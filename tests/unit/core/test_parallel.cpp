// parallel_indices: every index once on any thread count; the lowest
// failing index's exception rethrown after the threads stop.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>
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

// Runs 1000 indices on `threads` threads where indices `bad` and
// `also_bad` throw; returns the message rethrown ("" if none) and counts
// the indices that ran.
std::string failure_of(int threads, std::size_t bad, std::size_t also_bad, std::atomic<int>& ran) {
  ran = 0;
  try {
    parallel_indices(1000, threads, [&](std::size_t i) {
      ++ran;
      if (i == bad || i == also_bad) throw std::runtime_error("index " + std::to_string(i));
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    });
  } catch (const std::runtime_error& e) {
    return e.what();
  }
  return "";
}

TEST(ParallelIndices, TheLowestFailingIndexIsRethrownAndWorkStops) {
  std::atomic<int> ran{0};
  // One thread stops right after the failing index.
  EXPECT_EQ(failure_of(1, 5, 9, ran), "index 5");
  EXPECT_EQ(ran, 6);
  // Several threads: the lower of two failures is the one reported, and
  // not every index runs.
  for (int round = 0; round < 5; ++round) {
    EXPECT_EQ(failure_of(3, 9, 5, ran), "index 5");
    EXPECT_LT(ran, 1000);
  }
}

}  // namespace
}  // namespace layers
