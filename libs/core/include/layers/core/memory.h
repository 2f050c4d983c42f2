// layers/core/memory.h -- process memory figures (Linux /proc), used by
// tests and benchmarks that check bounded memory, and how the process
// keeps memory it frees.
#pragma once

#include <cstddef>

namespace layers {

// Current resident set size in bytes (VmRSS), 0 if unavailable.
std::size_t resident_bytes();
// Peak resident set size in bytes (VmHWM), 0 if unavailable.
std::size_t peak_resident_bytes();

// Lets glibc's malloc keep what the process frees for its next
// allocations instead of handing it back to the kernel: blocks up to 32
// MiB (glibc's largest) come from the heap rather than from fresh mmaps,
// and freed memory at the heap's top is kept. A model step allocates and
// frees the same large tensors every step; from fresh mmaps each one
// costs a page fault and zeroing per 4 KiB page, which measured 4x the
// step's own work at 12k garment vertices (docs/benchmarks.md, "Memory
// reuse"). Leaves malloc alone when the user set its tunables
// (GLIBC_TUNABLES or MALLOC_MMAP_THRESHOLD_). Returns whether it changed them.
bool keep_freed_memory();

}  // namespace layers
