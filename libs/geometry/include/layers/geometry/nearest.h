// layers/geometry/nearest.h -- nearest-point queries over a fixed point set
// (a kd-tree; nanoflann stays inside the library). Distances are Euclidean,
// not squared. Queries are const and may run from several threads at once.
#pragma once

#include <limits>
#include <memory>
#include <vector>

#include "layers/geometry/mesh.h"

namespace layers::geometry {

struct Neighbour {
  int index = -1;  // -1: none (empty index or non-finite query)
  float distance = std::numeric_limits<float>::infinity();
};

class PointIndex {
 public:
  // An empty index: every query finds nothing.
  PointIndex();
  // Copies the points and builds the tree. Throws layers::Error if a point
  // is not finite.
  explicit PointIndex(Points points);
  ~PointIndex();
  PointIndex(PointIndex&&) noexcept;
  PointIndex& operator=(PointIndex&&) noexcept;
  PointIndex(const PointIndex&) = delete;
  PointIndex& operator=(const PointIndex&) = delete;

  int size() const;
  const Points& points() const;

  // The closest point (ties: any of them).
  Neighbour nearest(const Eigen::RowVector3f& query) const;
  // Up to k closest points, closest first (fewer if the set is smaller).
  std::vector<Neighbour> knn(const Eigen::RowVector3f& query, int k) const;
  // All points with distance < radius (strictly), closest first.
  std::vector<Neighbour> within(const Eigen::RowVector3f& query, float radius) const;
  // nearest() for each row of `queries`: indices (-1 where none), and the
  // distances if `distances` is given.
  Eigen::VectorXi nearest_all(const Points& queries, Eigen::VectorXf* distances = nullptr) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace layers::geometry
