// keep_freed_memory(): a large block freed and allocated again reuses the
// process's pages instead of faulting in fresh ones; a user's own malloc
// settings are left alone.
#include <gtest/gtest.h>

#include <sys/resource.h>

#include <cstdlib>
#include <vector>

#include "layers/core/memory.h"

namespace {

// Minor page faults of `rounds` rounds like a model step's: blocks of a
// few sizes (3-24 MiB) allocated and touched page by page, all alive at
// once, then freed.
long faults_of(int rounds) {
  rusage before{}, after{};
  getrusage(RUSAGE_SELF, &before);
  for (int r = 0; r < rounds; ++r) {
    std::vector<volatile char*> blocks;
    for (std::size_t mib : {6, 12, 6, 24, 3}) {
      const std::size_t bytes = mib << 20;
      volatile char* p = static_cast<volatile char*>(std::malloc(bytes));
      for (std::size_t i = 0; i < bytes; i += 4096) p[i] = 1;
      blocks.push_back(p);
    }
    for (volatile char* p : blocks) std::free(const_cast<char*>(p));
  }
  getrusage(RUSAGE_SELF, &after);
  return after.ru_minflt - before.ru_minflt;
}

}  // namespace

TEST(Memory, FreedBlocksAreKeptForTheNextAllocation) {
  unsetenv("GLIBC_TUNABLES");
  unsetenv("MALLOC_MMAP_THRESHOLD_");
  ASSERT_TRUE(layers::keep_freed_memory());
  faults_of(1);  // the heap grows once
  // glibc's defaults fault about 13,000 pages in again per round here
  // (104,224 over 8 rounds, measured); kept, none.
  EXPECT_LT(faults_of(8), 512) << "the rounds faulted their pages in again";
}

TEST(Memory, AUsersMallocSettingsWin) {
  setenv("MALLOC_MMAP_THRESHOLD_", "131072", 1);
  EXPECT_FALSE(layers::keep_freed_memory());
  unsetenv("MALLOC_MMAP_THRESHOLD_");
}
