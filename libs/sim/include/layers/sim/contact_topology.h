// layers/sim/contact_topology.h -- the connectivity a contact query needs
// from a triangle mesh (the body or a garment): faces, the faces around
// each vertex, which face edges lie on an open boundary (a hem, a cuff),
// and the longest edge (which bounds how far a surface point can be from
// its nearest vertex). Built once per mesh; positions live elsewhere.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "layers/geometry/mesh.h"

namespace layers::sim {

struct ContactTopology {
  std::vector<std::array<int, 3>> faces;
  std::vector<int> face_offsets;  // num_vertices + 1 entries
  std::vector<int> vertex_faces;  // faces of vertex i: [face_offsets[i], face_offsets[i+1])
  // Per face, bit k is set when the edge from corner k to corner (k+1)%3
  // belongs to this face only.
  std::vector<std::uint8_t> boundary_edges;
  std::vector<std::uint8_t> boundary_vertex;  // 1 for vertices on an open boundary
  double max_edge_length = 0;                 // in the reference positions given to build()

  // How far a point of the surface can be from its nearest vertex: every
  // point of a triangle lies within (longest edge)/sqrt(3) of a corner; with
  // a margin for deformation since build(). A search for the nearest vertex
  // within (contact distance + reach()) finds one whenever the surface is
  // within the contact distance.
  double reach() const { return 0.6 * max_edge_length; }

  int num_vertices() const { return face_offsets.empty() ? 0 : static_cast<int>(face_offsets.size()) - 1; }
  int num_faces() const { return static_cast<int>(faces.size()); }

  // Validates the faces against the reference positions (InputError naming
  // `what`) and builds the tables.
  static ContactTopology build(const geometry::Faces& faces, const geometry::Points& reference,
                               const std::string& what);
};

}  // namespace layers::sim
