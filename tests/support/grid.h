// tests/support/grid.h -- the one face list of a synthetic grid garment
// (torch-free): a rows x cols vertex grid, vertex (r, c) = r * cols + c,
// two triangles per cell. Every fixture that builds a grid scene takes its
// faces from here (tensor form: grid_tensor.h).
#pragma once

#include <cstdint>
#include <vector>

namespace layers::test {

// Faces [F*3] of the grid: cell (r, c) with corners a = (r, c), b = (r, c+1),
// d = (r+1, c), e = (r+1, c+1) gives (a, b, e) then (a, e, d). closed: the
// grid wraps around a cylinder, the last column joining the first.
template <class Index = std::int64_t>
std::vector<Index> grid_faces(int rows, int cols, bool closed = false) {
  std::vector<Index> faces;
  const int cells = closed ? cols : cols - 1;
  for (int r = 0; r + 1 < rows; ++r) {
    for (int c = 0; c < cells; ++c) {
      const Index a = static_cast<Index>(r * cols + c), b = static_cast<Index>(r * cols + (c + 1) % cols);
      const Index d = a + static_cast<Index>(cols), e = b + static_cast<Index>(cols);
      faces.insert(faces.end(), {a, b, e, a, e, d});
    }
  }
  return faces;
}

}  // namespace layers::test
