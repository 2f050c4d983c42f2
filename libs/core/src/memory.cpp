// Reads VmRSS / VmHWM from /proc/self/status; malloc's keeping of freed
// memory (see memory.h).
#include "layers/core/memory.h"

#include <malloc.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

namespace layers {
namespace {
std::size_t status_kib(const char* key) {
  std::ifstream in("/proc/self/status");
  std::string line;
  const std::string prefix = std::string(key) + ":";
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) == 0) {
      std::istringstream fields(line.substr(prefix.size()));
      std::size_t kib = 0;
      fields >> kib;
      return kib;
    }
  }
  return 0;
}
}  // namespace

std::size_t resident_bytes() { return status_kib("VmRSS") * 1024; }
std::size_t peak_resident_bytes() { return status_kib("VmHWM") * 1024; }

bool keep_freed_memory() {
  if (std::getenv("GLIBC_TUNABLES") || std::getenv("MALLOC_MMAP_THRESHOLD_")) return false;
  constexpr int kLargest = 32 * 1024 * 1024;  // glibc refuses a larger mmap threshold
  const bool mmap = mallopt(M_MMAP_THRESHOLD, kLargest) == 1;
  const bool trim = mallopt(M_TRIM_THRESHOLD, std::numeric_limits<int>::max()) == 1;
  return mmap && trim;
}

}  // namespace layers
