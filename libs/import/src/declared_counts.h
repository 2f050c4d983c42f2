// declared_counts.h (internal) -- what a file says it holds, checked
// before assimp reads it: a glTF's JSON, a GLB's header and chunk, the
// buffer views and accessors within their buffers (counts of 1 or more), a
// PLY whole (header, rows, list counts, face indices: assimp 5.2 crashed
// on damaged ones), and counts against the file's size. A PLY header's element
// counts and a binary STL's facet count are read and each element given
// the fewest bytes it can take; a file too small for what it declares is
// refused with one line naming the count (assimp would allocate for the
// declared count first: 23.5 GB for a 227-byte PLY declaring 2e9 vertices).
#pragma once

#include <string>

namespace layers::import::detail {

// InputError (path, the count's field, ...) when `path` (.ply or .stl,
// other extensions pass) declares more than its size can hold.
void check_declared_counts(const std::string& path);

}  // namespace layers::import::detail
