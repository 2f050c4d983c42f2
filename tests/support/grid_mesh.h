// tests/support/grid_mesh.h -- hand-checkable meshes for geometry tests:
// an n x n vertex grid over the unit square at height z, normals +z.
#pragma once

#include "layers/geometry/mesh.h"

namespace layers::test {

inline geometry::TriMesh unit_square_grid(int n, float z) {
  geometry::TriMesh m;
  m.vertices.resize(n * n, 3);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.vertices.row(j * n + i) << i / float(n - 1), j / float(n - 1), z;
  m.faces.resize(2 * (n - 1) * (n - 1), 3);
  int f = 0;
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      int a = j * n + i, b = a + 1, c = a + n, d = c + 1;
      m.faces.row(f++) << a, b, d;
      m.faces.row(f++) << a, d, c;
    }
  return m;
}

}  // namespace layers::test
