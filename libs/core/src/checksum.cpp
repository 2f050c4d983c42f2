// 64-bit FNV-1a (see checksum.h).
#include "layers/core/checksum.h"

#include <cstdio>

namespace layers {

ContentHash& ContentHash::add(const void* data, std::size_t bytes) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    h_ ^= p[i];
    h_ *= 1099511628211ull;
  }
  return *this;
}

std::string ContentHash::hex() const {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h_));
  return buf;
}

std::string content_hash(std::string_view text) { return ContentHash().add(text).hex(); }

}  // namespace layers
