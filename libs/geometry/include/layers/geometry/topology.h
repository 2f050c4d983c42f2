// layers/geometry/topology.h -- mesh connectivity: unique undirected edges
// (and their lengths), open-boundary edges and vertices and vertex adjacency (compressed rows: the neighbours of vertex
// i are neighbours[offsets[i] .. offsets[i+1])).
#pragma once

#include <vector>

#include "layers/geometry/mesh.h"

namespace layers::geometry {

// Every undirected edge once, as (i, j) with i < j, sorted by (i, j).
Edges unique_edges(const Faces& faces);

struct Adjacency {
  std::vector<int> offsets;     // num_vertices + 1 entries
  std::vector<int> neighbours;  // sorted ascending within each vertex

  int num_vertices() const { return offsets.empty() ? 0 : static_cast<int>(offsets.size()) - 1; }
  int degree(int v) const { return offsets[v + 1] - offsets[v]; }
  const int* begin(int v) const { return neighbours.data() + offsets[v]; }
  const int* end(int v) const { return neighbours.data() + offsets[v + 1]; }
};

// Length of every edge (rows of `edges`) in `points`, in double precision.
Eigen::VectorXd edge_lengths(const Points& points, const Edges& edges);

// The edges used by one face only (an open boundary: a hem, a cuff, a
// neckline), as (i, j) with i < j, sorted by (i, j).
Edges boundary_edges(const Faces& faces);

// 1 for every vertex on an open boundary (an end of a boundary edge), 0
// otherwise; `num_vertices` entries.
std::vector<char> boundary_vertices(const Faces& faces, int num_vertices);

// Vertex-to-vertex adjacency through mesh edges. Indices must lie in
// [0, num_vertices); `num_vertices` may exceed the largest index used
// (isolated vertices have no neighbours). The Edges overload expects each
// undirected edge once, as unique_edges() returns them.
Adjacency vertex_adjacency(const Faces& faces, int num_vertices);
Adjacency vertex_adjacency(const Edges& edges, int num_vertices);

}  // namespace layers::geometry
