// h5_heap_check.h (internal) -- HDF5's global heap checked before libhdf5
// reads from it. Variable-length strings (in files written before strings
// were stored fixed-length, h5_io.cpp) live in global heap collections,
// which have no checksum; libhdf5 1.10 follows a damaged object size past
// its collection and dies (tests/fuzz/libhdf5-crashes). Before such a read,
// every collection of the file is walked from its bytes.
#pragma once

#include <string>

namespace layers::data::h5 {

// Throws InputError (file, "global heap", ...) when a global heap
// collection of `path` holds an object that runs past the collection or
// the collection runs past the file. A collection is recognised by its
// signature, version 1 and zero reserved bytes ("GCOL\1\0\0\0"). The
// verdict is kept per path, size and modification time (call under the
// HDF5 lock).
void check_global_heaps(const std::string& path);

}  // namespace layers::data::h5
