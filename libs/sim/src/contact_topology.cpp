// Builds ContactTopology: faces around each vertex, open-boundary edges and
// the longest edge (see contact_topology.h).
#include "layers/sim/contact_topology.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "layers/core/error.h"

namespace layers::sim {

ContactTopology ContactTopology::build(const geometry::Faces& faces, const geometry::Points& reference,
                                       const std::string& what) {
  const int nv = static_cast<int>(reference.rows());
  geometry::validate(faces, nv, what);
  ContactTopology t;
  const int nf = static_cast<int>(faces.rows());
  t.faces.resize(nf);
  t.face_offsets.assign(nv + 1, 0);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      t.faces[f][k] = faces(f, k);
      ++t.face_offsets[faces(f, k) + 1];
    }
  }
  for (int i = 0; i < nv; ++i) t.face_offsets[i + 1] += t.face_offsets[i];
  t.vertex_faces.resize(t.face_offsets[nv]);
  std::vector<int> fill(t.face_offsets.begin(), t.face_offsets.end() - 1);
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) t.vertex_faces[fill[faces(f, k)]++] = f;
  }

  // Each directed face edge keyed by its sorted vertex pair; an undirected
  // edge used by exactly one face is on the boundary.
  std::vector<std::pair<std::pair<int, int>, int>> keyed;  // ((lo, hi), face * 3 + corner)
  keyed.reserve(3 * static_cast<std::size_t>(nf));
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) {
      const int a = faces(f, k), b = faces(f, (k + 1) % 3);
      keyed.push_back({{std::min(a, b), std::max(a, b)}, f * 3 + k});
      const double len = (reference.row(a) - reference.row(b)).cast<double>().norm();
      if (!std::isfinite(len)) {
        throw InputError::message(what, "vertices", "non-finite coordinates at vertex " + std::to_string(a));
      }
      t.max_edge_length = std::max(t.max_edge_length, len);
    }
  }
  std::sort(keyed.begin(), keyed.end());
  t.boundary_edges.assign(nf, 0);
  t.boundary_vertex.assign(nv, 0);
  for (std::size_t i = 0; i < keyed.size();) {
    std::size_t j = i + 1;
    while (j < keyed.size() && keyed[j].first == keyed[i].first) ++j;
    if (j - i == 1) {
      const int f = keyed[i].second / 3, k = keyed[i].second % 3;
      t.boundary_edges[f] |= static_cast<std::uint8_t>(1u << k);
      t.boundary_vertex[keyed[i].first.first] = 1;
      t.boundary_vertex[keyed[i].first.second] = 1;
    }
    i = j;
  }
  return t;
}

}  // namespace layers::sim
