// The checks of a user's garment mesh (see mesh_checks.h).
#include "layers/import/mesh_checks.h"

#include <Eigen/Geometry>

#include <map>
#include <sstream>
#include <utility>

#include "layers/core/error.h"

namespace layers::import {

void check_cloth_mesh(const geometry::TriMesh& mesh, const std::string& file) {
  if (mesh.faces.rows() == 0) throw InputError(file, "faces", "a triangle mesh", "no face");
  geometry::validate(mesh, file);
  if (!mesh.vertices.allFinite()) throw InputError(file, "vertices", "finite positions", "NaN or infinite values");
  const Eigen::RowVector3f extent = mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff();
  const double largest = extent.maxCoeff();
  if (largest < kMinExtent || largest > kMaxExtent) {
    std::ostringstream got;
    got << "a largest extent of " << largest << " m (centimetres or millimetres? set scale in the garment's .yaml)";
    std::ostringstream want;
    want << "a garment in metres, largest extent " << kMinExtent << "-" << kMaxExtent << " m";
    throw InputError(file, "scale", want.str(), got.str());
  }
  int degenerate = 0, first_degenerate = -1;
  std::map<std::pair<int, int>, int> edge_faces;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const int a = mesh.faces(f, 0), b = mesh.faces(f, 1), c = mesh.faces(f, 2);
    const Eigen::Vector3d pa = mesh.vertices.row(a).cast<double>(), pb = mesh.vertices.row(b).cast<double>(),
                          pc = mesh.vertices.row(c).cast<double>();
    const double area = 0.5 * (pb - pa).cross(pc - pa).norm();
    if (a == b || b == c || a == c || !(area >= geometry::kMinClothFaceArea)) {
      if (first_degenerate < 0) first_degenerate = static_cast<int>(f);
      ++degenerate;
    }
    for (const auto& [u, v] : {std::pair{a, b}, std::pair{b, c}, std::pair{c, a}})
      ++edge_faces[{std::min(u, v), std::max(u, v)}];
  }
  if (degenerate > 0)
    throw InputError(file, "faces",
                     "no degenerate face (area >= 1e-8 m^2, three distinct corners; `remesh: fit` in its side file "
                     "rebuilds the faces)",
                     std::to_string(degenerate) + " degenerate, the first face " + std::to_string(first_degenerate));
  // Winding: across an edge of two faces, each runs it the other way.
  std::map<std::pair<int, int>, int> directed;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f)
    for (int c = 0; c < 3; ++c) ++directed[{mesh.faces(f, c), mesh.faces(f, (c + 1) % 3)}];
  int flipped = 0;
  std::pair<int, int> first_flipped{-1, -1};
  for (const auto& [edge, count] : directed)
    if (count > 1 && edge_faces[{std::min(edge.first, edge.second), std::max(edge.first, edge.second)}] == 2) {
      if (flipped++ == 0) first_flipped = edge;
    }
  int non_manifold = 0;
  std::pair<int, int> first{-1, -1};
  for (const auto& [edge, count] : edge_faces) {
    if (count <= 2) continue;
    if (non_manifold++ == 0) first = edge;
  }
  if (non_manifold > 0)
    throw InputError(file, "faces", "a manifold mesh (every edge in one or two faces; open boundaries are fine)",
                     std::to_string(non_manifold) + " edges in three or more faces, the first between vertices " +
                         std::to_string(first.first) + " and " + std::to_string(first.second));
  if (flipped > 0)
    throw InputError(file, "faces", "faces wound one way (each shared edge run in opposite directions)",
                     std::to_string(flipped) + " edges whose two faces disagree, the first between vertices " +
                         std::to_string(first_flipped.first) + " and " + std::to_string(first_flipped.second));
  // Outward: area-weighted normals point away from the vertical axis
  // through the centroid on the whole (a garment wound inwards would be
  // pushed into the body by every contact).
  const Eigen::RowVector3d centre = mesh.vertices.cast<double>().colwise().mean();
  double outward = 0, total = 0;
  for (Eigen::Index f = 0; f < mesh.faces.rows(); ++f) {
    const Eigen::Vector3d a = mesh.vertices.row(mesh.faces(f, 0)).cast<double>(),
                          b = mesh.vertices.row(mesh.faces(f, 1)).cast<double>(),
                          c = mesh.vertices.row(mesh.faces(f, 2)).cast<double>();
    const Eigen::Vector3d n = (b - a).cross(c - a);  // twice the area
    Eigen::Vector3d r = (a + b + c) / 3.0 - centre.transpose();
    r.y() = 0;
    if (r.norm() < 1e-9) continue;
    outward += n.dot(r.normalized());
    total += n.norm();
  }
  if (total > 0 && outward < 0)
    throw InputError(file, "faces", "faces wound counter-clockwise seen from outside (normals away from the body)",
                     "normals pointing inwards on the whole (flip them in the modelling tool)");
}

}  // namespace layers::import
