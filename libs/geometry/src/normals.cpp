// Face and vertex normals (see normals.h). Sums run in double so that large
// meshes with tiny faces keep their precision.
#include "layers/geometry/normals.h"

#include <Eigen/Geometry>

namespace layers::geometry {
namespace {

// Cross product of the two edges leaving the first corner: its direction is
// the face normal and its length twice the face area.
Eigen::Vector3d doubled_area_normal(const Points& v, const Faces& faces, Eigen::Index f) {
  Eigen::Vector3d a = v.row(faces(f, 0)).cast<double>().transpose();
  Eigen::Vector3d b = v.row(faces(f, 1)).cast<double>().transpose();
  Eigen::Vector3d c = v.row(faces(f, 2)).cast<double>().transpose();
  return (b - a).cross(c - a);
}

Eigen::RowVector3f unit_or_zero(const Eigen::Vector3d& n) {
  double len = n.norm();
  if (!(len > 0.0)) return Eigen::RowVector3f::Zero();
  return (n / len).cast<float>().transpose();
}

}  // namespace

Points face_normals(const Points& vertices, const Faces& faces) {
  Points out(faces.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    out.row(f) = unit_or_zero(doubled_area_normal(vertices, faces, f));
  }
  return out;
}

Eigen::VectorXf face_areas(const Points& vertices, const Faces& faces) {
  Eigen::VectorXf out(faces.rows());
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    out(f) = static_cast<float>(0.5 * doubled_area_normal(vertices, faces, f).norm());
  }
  return out;
}

Points vertex_normals(const Points& vertices, const Faces& faces) {
  // The doubled-area normal already carries the area weight.
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> sum =
      Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>::Zero(vertices.rows(), 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    Eigen::RowVector3d n = doubled_area_normal(vertices, faces, f).transpose();
    for (int c = 0; c < 3; ++c) sum.row(faces(f, c)) += n;
  }
  Points out(vertices.rows(), 3);
  for (Eigen::Index i = 0; i < vertices.rows(); ++i) out.row(i) = unit_or_zero(sum.row(i).transpose());
  return out;
}

}  // namespace layers::geometry
