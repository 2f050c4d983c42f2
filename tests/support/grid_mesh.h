// tests/support/grid_mesh.h -- hand-checkable meshes for geometry tests:
// an n x n vertex grid over the unit square at height z, normals +z
// (faces from grid.h).
#pragma once

#include <vector>

#include "grid.h"
#include "layers/geometry/mesh.h"

namespace layers::test {

inline geometry::TriMesh unit_square_grid(int n, float z) {
  geometry::TriMesh m;
  m.vertices.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.vertices.row(j * n + i) << i / float(n - 1), j / float(n - 1), z;
  const std::vector<int> faces = grid_faces<int>(n, n);
  m.faces.resize(static_cast<Eigen::Index>(faces.size() / 3), 3);
  for (std::size_t f = 0; f < faces.size() / 3; ++f)
    m.faces.row(static_cast<Eigen::Index>(f)) << faces[3 * f], faces[3 * f + 1], faces[3 * f + 2];
  return m;
}

}  // namespace layers::test
