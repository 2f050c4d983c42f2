// keep_freed_memory(): a large block freed and allocated again reuses the
// process's pages instead of faulting in fresh ones; a user's own malloc
// settings are left alone.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstdlib>

#include "layers/core/memory.h"

namespace {

// Minor page faults of `rounds` allocations of `bytes`, each touched page
// by page and freed.
long faults_of(std::size_t bytes, int rounds) {
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  for (int r = 0; r < rounds; ++r) {
    volatile char* p = static_cast<volatile char*>(std::malloc(bytes));
    for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 1;
    std::free(const_cast<char*>(p));
  }
  getrusage(RUSAGE_SELF, &after);
  return after.ru_minflt - before.ru_minflt;
}

}  // namespace

TEST(Memory, FreedBlocksAreKeptForTheNextAllocation) {
  unsetenv("GLIBC_TUNABLES");
  unsetenv("MALLOC_MMAP_THRESHOLD_");
  ASSERT_TRUE(layers::keep_freed_memory());
  const std::size_t bytes = std::size_t{16} << 20;  // 4,096 pages: mmapped afresh by default
  faults_of(bytes, 1);                              // the heap grows once
  EXPECT_LT(faults_of(bytes, 8), 512) << "each round faulted its pages in again";
}

TEST(Memory, AUsersMallocSettingsWin) {
  setenv("MALLOC_MMAP_THRESHOLD_", "131072", 1);
  EXPECT_FALSE(layers::keep_freed_memory());
  unsetenv("MALLOC_MMAP_THRESHOLD_");
}
