// Reads VmRSS / VmHWM from /proc/self/status (see memory.h).
#include "layers/core/memory.h"

#include <fstream>
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

}  // namespace layers
