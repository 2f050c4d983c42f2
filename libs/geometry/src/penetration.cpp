// Nearest-vertex penetration test (see penetration.h).
#include "layers/geometry/penetration.h"

#include <limits>
#include <string>

#include "layers/core/error.h"
#include "layers/geometry/normals.h"
#include "layers/geometry/topology.h"

namespace layers::geometry {

Surface::Surface(Points vertices, Points normals) : normals_(std::move(normals)) {
  if (normals_.rows() != vertices.rows()) {
    throw Error("Surface: " + std::to_string(vertices.rows()) + " vertices but " + std::to_string(normals_.rows()) +
                " normals");
  }
  index_ = PointIndex(std::move(vertices));
}

Surface Surface::from_mesh(const TriMesh& mesh, const std::string& what, OpenEdges open) {
  validate(mesh, what);
  Surface surface(mesh.vertices, vertex_normals(mesh));
  if (open == OpenEdges::Ignore) surface.open_ = boundary_vertices(mesh.faces, mesh.num_vertices());
  return surface;
}

float Surface::offset(const Eigen::RowVector3f& x) const {
  Neighbour h = index_.nearest(x);
  if (h.index < 0 || (!open_.empty() && open_[static_cast<std::size_t>(h.index)]))
    return std::numeric_limits<float>::quiet_NaN();
  return (x - index_.points().row(h.index)).dot(normals_.row(h.index));
}

Eigen::VectorXf Surface::offsets(const Points& x) const {
  Eigen::VectorXf out(x.rows());
  for (Eigen::Index i = 0; i < x.rows(); ++i) out(i) = offset(x.row(i));
  return out;
}

Eigen::Array<bool, Eigen::Dynamic, 1> Surface::behind(const Points& x) const { return offsets(x).array() < 0.0f; }

Eigen::Index Surface::count_behind(const Points& x) const { return behind(x).count(); }

}  // namespace layers::geometry
