// target_file.h (private to layers::body) -- MakeHuman shape targets:
// gzip text, one `vertex dx dy dz` line per moved vertex ('#' comments),
// read with zlib. Offsets are returned as stored (decimetres).
#pragma once

#include <string>
#include <vector>

namespace layers::body {

struct ShapeTarget {
  std::vector<int> vertex;    // vertex index per entry
  std::vector<float> offset;  // 3 floats per entry
};

// Reads a .target.gz (or plain text) file. Throws InputError naming the
// file and line for an unreadable file, a malformed line or a vertex index
// outside [0, num_vertices).
ShapeTarget read_target(const std::string& path, int num_vertices);

}  // namespace layers::body
