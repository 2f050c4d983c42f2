// layers/core/checksum.h -- the toolkit's one content hash: 64-bit FNV-1a,
// written as 16 lower-case hex digits. Used for study fingerprints,
// checkpoint checksums and sequence content hashes; it detects damage and
// change, it is not a cryptographic hash.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

namespace layers {

class ContentHash {
 public:
  ContentHash& add(const void* data, std::size_t bytes);
  ContentHash& add(std::string_view text) { return add(text.data(), text.size()); }
  std::uint64_t value() const { return h_; }
  std::string hex() const;  // 16 hex digits

 private:
  std::uint64_t h_ = 1469598103934665603ull;
};

// ContentHash().add(text).hex().
std::string content_hash(std::string_view text);

}  // namespace layers
