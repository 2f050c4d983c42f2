// layers/geometry/penetration.h -- which points lie behind a surface.
//
// The test of docs/metrics.md (and of the paper's public code): for a
// point x, take the nearest surface vertex h and its unit vertex normal n;
// x is behind the surface when (x - h) . n < 0. It is cheap (one kd-tree
// query) and exact enough away from thin features; it is what the H- and
// L-collision metrics and the collision losses use.
//
// A surface made with OpenEdges::Ignore gives no verdict (offset NaN, not
// behind) for a point whose nearest vertex lies on an open edge of the mesh
// (a hem, a cuff, a neckline): such a point is beside the surface, not
// behind it. Our L-collision (metrics::l_collision_rate) tests outer garments
// that way; the paper's (metrics::l_collision_plain_rate) counts every point
// (OpenEdges::Count).
#pragma once

#include <string>
#include <vector>

#include <Eigen/Core>

#include "layers/geometry/mesh.h"
#include "layers/geometry/nearest.h"

namespace layers::geometry {

class Surface {
 public:
  enum class OpenEdges { Count, Ignore };

  // An empty surface: nothing is behind it.
  Surface() = default;
  // Vertices with their unit normals (same row count, else layers::Error).
  Surface(Points vertices, Points normals);
  // Uses the mesh's area-weighted vertex normals; validates the faces
  // (InputError naming `what`). `open`: see the file comment.
  static Surface from_mesh(const TriMesh& mesh, const std::string& what = "surface", OpenEdges open = OpenEdges::Count);

  int size() const { return index_.size(); }
  const Points& vertices() const { return index_.points(); }
  const Points& normals() const { return normals_; }
  const PointIndex& index() const { return index_; }

  // (x - h) . n for the nearest vertex h; NaN when there is none (empty
  // surface or non-finite x) or, with OpenEdges::Ignore, when h is on an
  // open edge.
  float offset(const Eigen::RowVector3f& x) const;
  Eigen::VectorXf offsets(const Points& x) const;

  // offset(x) < 0. A NaN offset counts as not behind.
  bool behind(const Eigen::RowVector3f& x) const { return offset(x) < 0.0f; }
  Eigen::Array<bool, Eigen::Dynamic, 1> behind(const Points& x) const;
  Eigen::Index count_behind(const Points& x) const;

 private:
  PointIndex index_;
  Points normals_{0, 3};
  std::vector<char> open_;  // per vertex, only with OpenEdges::Ignore
};

}  // namespace layers::geometry
