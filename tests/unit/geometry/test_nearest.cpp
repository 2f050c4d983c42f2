// PointIndex against brute force on random points.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "layers/core/error.h"
#include "layers/geometry/nearest.h"

namespace g = layers::geometry;

namespace {

g::Points random_points(int n, std::mt19937& rng) {
  std::uniform_real_distribution<float> u(-1.0f, 1.0f);
  g::Points p(n, 3);
  for (int i = 0; i < n; ++i) p.row(i) << u(rng), u(rng), u(rng);
  return p;
}

// Distances from q to every point, sorted, as (distance, index).
std::vector<std::pair<float, int>> brute_force(const g::Points& p, const Eigen::RowVector3f& q) {
  std::vector<std::pair<float, int>> d;
  for (int i = 0; i < p.rows(); ++i) d.emplace_back((p.row(i) - q).norm(), i);
  std::sort(d.begin(), d.end());
  return d;
}

}  // namespace

TEST(PointIndex, NearestKnnAndRadiusMatchBruteForce) {
  std::mt19937 rng(7);
  g::Points pts = random_points(2000, rng);
  g::PointIndex index(pts);
  ASSERT_EQ(index.size(), 2000);
  g::Points queries = random_points(200, rng);
  Eigen::VectorXf dist;
  Eigen::VectorXi nearest = index.nearest_all(queries, &dist);
  for (int q = 0; q < queries.rows(); ++q) {
    auto truth = brute_force(pts, queries.row(q));
    EXPECT_NEAR(dist(q), truth[0].first, 1e-5f);
    EXPECT_NEAR((pts.row(nearest(q)) - queries.row(q)).norm(), truth[0].first, 1e-5f);

    auto knn = index.knn(queries.row(q), 8);
    ASSERT_EQ(knn.size(), 8u);
    for (int k = 0; k < 8; ++k) EXPECT_NEAR(knn[k].distance, truth[k].first, 1e-5f) << "k=" << k;

    const float radius = 0.2f;
    auto hits = index.within(queries.row(q), radius);
    auto expected = std::count_if(truth.begin(), truth.end(), [&](auto& t) { return t.first < radius; });
    ASSERT_EQ(static_cast<long>(hits.size()), static_cast<long>(expected));
    for (std::size_t k = 0; k < hits.size(); ++k) {
      EXPECT_NEAR(hits[k].distance, truth[k].first, 1e-5f);
      if (k > 0) {
        EXPECT_LE(hits[k - 1].distance, hits[k].distance);
      }
    }
  }
}

TEST(PointIndex, SurvivesMove) {
  std::mt19937 rng(1);
  g::Points pts = random_points(50, rng);
  g::PointIndex a(pts);
  g::PointIndex b(std::move(a));
  g::PointIndex c;
  c = std::move(b);
  EXPECT_EQ(c.nearest(pts.row(17)).index, 17);
  EXPECT_EQ(c.nearest(pts.row(17)).distance, 0.0f);
}

TEST(PointIndex, EmptyAndDegenerateQueries) {
  g::PointIndex empty;
  EXPECT_EQ(empty.size(), 0);
  EXPECT_EQ(empty.nearest(Eigen::RowVector3f(0, 0, 0)).index, -1);
  EXPECT_TRUE(empty.knn(Eigen::RowVector3f(0, 0, 0), 3).empty());

  g::Points pts(3, 3);
  pts << 0, 0, 0, 1, 0, 0, 0, 2, 0;
  g::PointIndex index(pts);
  EXPECT_EQ(index.knn(Eigen::RowVector3f(0, 0, 0), 10).size(), 3u);  // fewer than k
  EXPECT_TRUE(index.knn(Eigen::RowVector3f(0, 0, 0), 0).empty());
  float nan = std::nanf("");
  EXPECT_EQ(index.nearest(Eigen::RowVector3f(nan, 0, 0)).index, -1);
  EXPECT_TRUE(index.within(Eigen::RowVector3f(0, 0, 0), 1.0f).size() == 1u);  // strict radius
}

TEST(PointIndex, RejectsNonFinitePoints) {
  g::Points pts(2, 3);
  pts << 0, 0, 0, std::nanf(""), 0, 0;
  try {
    g::PointIndex index(pts);
    FAIL() << "no error";
  } catch (const layers::Error& e) {
    EXPECT_STREQ(e.what(), "PointIndex: point 1 of 2 is not finite");
  }
}
