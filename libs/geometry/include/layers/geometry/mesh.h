// layers/geometry/mesh.h -- point sets and triangle meshes.
//
// layers::geometry owns the mesh-level maths the rest of the toolkit shares:
// the TriMesh type (row-major float vertices, int faces), face and vertex
// normals, unique edges and vertex adjacency, a kd-tree over a point set for
// nearest / k-nearest / radius queries, and the nearest-vertex penetration
// test of docs/metrics.md. Units are whatever the caller uses (metres
// everywhere in layers). It depends on layers::core and Eigen only.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

namespace layers::geometry {

// N points, one per row (x, y, z). Row-major so that a [N,3] float buffer
// (HDF5 dataset, torch tensor) maps onto it without reordering.
using Points = Eigen::Matrix<float, Eigen::Dynamic, 3, Eigen::RowMajor>;
// F triangles as vertex indices, one per row.
using Faces = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;
// E edges as vertex index pairs, one per row.
using Edges = Eigen::Matrix<int, Eigen::Dynamic, 2, Eigen::RowMajor>;

struct TriMesh {
  Points vertices;
  Faces faces;

  int num_vertices() const { return static_cast<int>(vertices.rows()); }
  int num_faces() const { return static_cast<int>(faces.rows()); }
};

// The smallest rest area of a cloth face (m^2): the simulator's lumped
// masses divide by it, and a user's garment file is checked against the
// same bound when it is read (import/mesh_checks.h).
inline constexpr double kMinClothFaceArea = 1e-8;

// Checks that every face index lies in [0, num_vertices) and that no face
// repeats a vertex; throws layers::InputError naming `what` (e.g. a file
// and dataset path), the face and the offending index.
void validate(const Faces& faces, int num_vertices, const std::string& what);
inline void validate(const TriMesh& mesh, const std::string& what) { validate(mesh.faces, mesh.num_vertices(), what); }

// Joins meshes into one (vertex indices of later meshes are offset), e.g.
// all inner garments of a scene as one surface.
TriMesh concatenate(const std::vector<TriMesh>& meshes);

}  // namespace layers::geometry
