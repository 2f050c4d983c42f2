// PointIndex over a nanoflann kd-tree (nanoflann 1.4 API: dataset adaptor
// + KDTreeSingleIndexAdaptor, squared L2 distances inside).
#include "layers/geometry/nearest.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>

#include <nanoflann.hpp>

#include "layers/core/error.h"

namespace layers::geometry {
namespace {

// nanoflann's view of a Points matrix.
struct PointsAdaptor {
  const Points* points;
  std::size_t kdtree_get_point_count() const { return static_cast<std::size_t>(points->rows()); }
  float kdtree_get_pt(std::size_t i, std::size_t dim) const {
    return (*points)(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(dim));
  }
  template <class BBox>
  bool kdtree_get_bbox(BBox&) const {
    return false;  // let nanoflann compute it
  }
};

using Tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PointsAdaptor>, PointsAdaptor, 3,
                                                 std::uint32_t>;

bool finite(const Eigen::RowVector3f& q) { return q.allFinite(); }

}  // namespace

struct PointIndex::Impl {
  Points points;
  PointsAdaptor adaptor{&points};
  Tree tree;

  explicit Impl(Points p)
      : points(std::move(p)), tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(/*leaf_max_size=*/16)) {}
};

PointIndex::PointIndex() : PointIndex(Points(0, 3)) {}

PointIndex::PointIndex(Points points) {
  for (Eigen::Index i = 0; i < points.rows(); ++i) {
    if (!points.row(i).allFinite()) {
      throw Error("PointIndex: point " + std::to_string(i) + " of " + std::to_string(points.rows()) + " is not finite");
    }
  }
  // Impl's constructor builds the tree over its own copy of the points, so
  // the adaptor's pointer stays valid when the PointIndex moves.
  impl_ = std::make_unique<Impl>(std::move(points));
}

PointIndex::~PointIndex() = default;
PointIndex::PointIndex(PointIndex&&) noexcept = default;
PointIndex& PointIndex::operator=(PointIndex&&) noexcept = default;

int PointIndex::size() const { return impl_ ? static_cast<int>(impl_->points.rows()) : 0; }

const Points& PointIndex::points() const {
  static const Points empty(0, 3);
  return impl_ ? impl_->points : empty;
}

Neighbour PointIndex::nearest(const Eigen::RowVector3f& query) const {
  std::vector<Neighbour> one = knn(query, 1);
  return one.empty() ? Neighbour{} : one.front();
}

std::vector<Neighbour> PointIndex::knn(const Eigen::RowVector3f& query, int k) const {
  std::vector<Neighbour> out;
  if (k <= 0 || size() == 0 || !finite(query)) return out;
  std::size_t want = std::min<std::size_t>(static_cast<std::size_t>(k), static_cast<std::size_t>(size()));
  std::vector<std::uint32_t> idx(want);
  std::vector<float> dist2(want);
  std::size_t found = impl_->tree.knnSearch(query.data(), want, idx.data(), dist2.data());
  out.reserve(found);
  for (std::size_t i = 0; i < found; ++i) out.push_back({static_cast<int>(idx[i]), std::sqrt(dist2[i])});
  return out;
}

std::vector<Neighbour> PointIndex::within(const Eigen::RowVector3f& query, float radius) const {
  std::vector<Neighbour> out;
  if (!(radius >= 0.0f) || size() == 0 || !finite(query)) return out;
  std::vector<std::pair<std::uint32_t, float>> hits;
  nanoflann::SearchParams params;
  params.sorted = true;
  impl_->tree.radiusSearch(query.data(), radius * radius, hits, params);
  out.reserve(hits.size());
  for (const auto& [i, d2] : hits) out.push_back({static_cast<int>(i), std::sqrt(d2)});
  return out;
}

Eigen::VectorXi PointIndex::nearest_all(const Points& queries, Eigen::VectorXf* distances) const {
  Eigen::VectorXi idx(queries.rows());
  if (distances) distances->resize(queries.rows());
  for (Eigen::Index q = 0; q < queries.rows(); ++q) {
    Neighbour n = nearest(queries.row(q));
    idx(q) = n.index;
    if (distances) (*distances)(q) = n.distance;
  }
  return idx;
}

}  // namespace layers::geometry
