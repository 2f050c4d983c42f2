// layers/core/memory.h -- process memory figures (Linux /proc), used by
// tests and benchmarks that check bounded memory.
#pragma once

#include <cstddef>

namespace layers {

// Current resident set size in bytes (VmRSS), 0 if unavailable.
std::size_t resident_bytes();
// Peak resident set size in bytes (VmHWM), 0 if unavailable.
std::size_t peak_resident_bytes();

}  // namespace layers
