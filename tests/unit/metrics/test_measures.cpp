// Metrics on cases computable by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "grid_mesh.h"
#include "layers/core/error.h"
#include "layers/metrics/measures.h"

namespace g = layers::geometry;
namespace metrics = layers::metrics;

namespace {

g::Points points(std::initializer_list<Eigen::RowVector3f> rows) {
  g::Points p(static_cast<Eigen::Index>(rows.size()), 3);
  Eigen::Index i = 0;
  for (const auto& r : rows) p.row(i++) = r;
  return p;
}

}  // namespace

TEST(Metrics, TranslationBy3mmGives3mm) {
  g::Points truth = g::Points::Zero(5, 3);
  g::Points pred = truth;
  pred.col(1).setConstant(0.003f);
  EXPECT_NEAR(metrics::euclidean_error_mm(pred, truth), 3.0, 1e-6);

  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-0.5f, 0.5f);
  g::Points body_like(1000, 3);
  for (int i = 0; i < 1000; ++i) body_like.row(i) << u(rng), u(rng) + 1.0f, u(rng);
  g::Points moved = body_like.rowwise() + Eigen::RowVector3f(0.0018f, 0.0f, -0.0024f);  // |d| = 3 mm
  EXPECT_NEAR(metrics::euclidean_error_mm(moved, body_like), 3.0, 1e-3);
  EXPECT_DOUBLE_EQ(metrics::euclidean_error_mm(body_like, body_like), 0.0);
}

TEST(Metrics, ErrorChecksShapesAndPropagatesNaN) {
  EXPECT_THROW(metrics::euclidean_error_mm(g::Points::Zero(3, 3), g::Points::Zero(4, 3)), layers::Error);
  EXPECT_THROW(metrics::euclidean_error_mm(g::Points(0, 3), g::Points(0, 3)), layers::Error);
  g::Points pred = g::Points::Zero(2, 3);
  pred(1, 0) = std::nanf("");
  EXPECT_TRUE(std::isnan(metrics::euclidean_error_mm(pred, g::Points::Zero(2, 3))));
}

TEST(Metrics, HCollisionAgainstABodyPlane) {
  g::TriMesh body = layers::test::unit_square_grid(11, 0.0f);
  g::Points garment = points({{0.1f, 0.1f, 0.02f},
                              {0.5f, 0.5f, -0.01f},
                              {0.33f, 0.71f, 0.005f},
                              {0.9f, 0.2f, -0.2f},
                              {0.2f, 0.8f, 0.3f},
                              {0.6f, 0.4f, 0.0f},  // on the surface: not behind
                              {0.7f, 0.7f, 0.1f},
                              {0.45f, 0.05f, -0.001f},
                              {0.95f, 0.95f, 0.01f},
                              {0.05f, 0.5f, 0.2f}});
  EXPECT_DOUBLE_EQ(metrics::h_collision_rate(garment, body), 0.3);
  garment(1, 0) = std::nanf("");  // a diverged vertex counts as not behind
  EXPECT_DOUBLE_EQ(metrics::h_collision_rate(garment, body), 0.2);
}

TEST(Metrics, LCollisionAgainstAnInnerPlane) {
  g::TriMesh inner = layers::test::unit_square_grid(6, 0.1f);
  g::Points outer = points({{0.5f, 0.5f, 0.12f}, {0.2f, 0.3f, 0.08f}, {0.7f, 0.1f, 0.15f}, {0.9f, 0.9f, 0.11f}});
  EXPECT_DOUBLE_EQ(metrics::l_collision_rate(outer, inner), 0.25);
  // Two inner garments joined into one surface: the second, higher one
  // (z = 0.13) is nearest to the first outer vertex, now behind it.
  g::TriMesh upper = layers::test::unit_square_grid(6, 0.13f);
  g::TriMesh both = g::concatenate({inner, upper});
  EXPECT_DOUBLE_EQ(metrics::l_collision_rate(outer, both), 0.5);
}

TEST(Metrics, LCollisionIgnoresOuterVerticesBesideAnOpenEdge) {
  // A jacket hanging past the hem of a shorter inner garment: its vertices
  // are below the inner surface's plane but beside its open edge, not
  // behind it; one vertex under the middle of the inner garment is.
  g::TriMesh inner = layers::test::unit_square_grid(6, 0.1f);
  g::Points outer = points({{1.1f, 0.5f, 0.05f}, {-0.1f, 0.3f, 0.0f}, {0.5f, 0.5f, 0.05f}, {0.3f, 0.7f, 0.2f}});
  EXPECT_DOUBLE_EQ(metrics::l_collision_rate(outer, inner), 0.25);
  // The plain nearest-vertex test (the paper's L-collision) counts the first two as well.
  EXPECT_DOUBLE_EQ(metrics::l_collision_plain_rate(outer, inner), 0.75);
}

namespace {

// A hand-made inner garment: a tube of radius 0.15 around the y axis, three
// rings of 8 vertices at y = 0 (the hem), 0.1 and 0.2 (the neckline), faces
// counter-clockwise seen from outside (normals point away from the axis).
g::TriMesh open_tube() {
  constexpr int kRing = 8, kRows = 3;
  const float pi = 3.14159265f;
  g::TriMesh tube;
  tube.vertices.resize(kRing * kRows, 3);
  for (int i = 0; i < kRows; ++i)
    for (int j = 0; j < kRing; ++j) {
      const float a = 2.0f * pi * static_cast<float>(j) / kRing;
      tube.vertices.row(i * kRing + j) << 0.15f * std::cos(a), 0.1f * static_cast<float>(i), 0.15f * std::sin(a);
    }
  tube.faces.resize(2 * kRing * (kRows - 1), 3);
  int f = 0;
  for (int i = 0; i + 1 < kRows; ++i)
    for (int j = 0; j < kRing; ++j) {
      const int a = i * kRing + j, b = i * kRing + (j + 1) % kRing, c = a + kRing, d = b + kRing;
      tube.faces.row(f++) << a, c, b;
      tube.faces.row(f++) << b, c, d;
    }
  return tube;
}

}  // namespace

TEST(Metrics, PlainLCollisionCountsBeyondTheHemOursDoesNot) {
  const g::TriMesh inner = open_tube();
  // Below the hem and nearer the axis than the hem vertex (0.15, 0, 0):
  // behind that vertex's normal plane, but beside the garment.
  const g::Points beyond_hem = points({{0.12f, -0.03f, 0.0f}});
  EXPECT_DOUBLE_EQ(metrics::l_collision_plain_rate(beyond_hem, inner), 1.0) << "the paper's rule counts it";
  EXPECT_DOUBLE_EQ(metrics::l_collision_rate(beyond_hem, inner), 0.0) << "the open-edge rule does not";
  // Clearly outside the tube at mid height: in front for both rules.
  const g::Points in_front = points({{0.25f, 0.1f, 0.0f}});
  EXPECT_DOUBLE_EQ(metrics::l_collision_plain_rate(in_front, inner), 0.0);
  EXPECT_DOUBLE_EQ(metrics::l_collision_rate(in_front, inner), 0.0);
  // Together with one inside the tube at mid height (nearest vertex not on
  // an open edge: behind for both) and one in front on the other side.
  const g::Points all = points({{0.12f, -0.03f, 0.0f}, {0.25f, 0.1f, 0.0f}, {0.12f, 0.1f, 0.0f}, {-0.3f, 0.1f, 0.0f}});
  EXPECT_DOUBLE_EQ(metrics::l_collision_plain_rate(all, inner), 0.5);
  EXPECT_DOUBLE_EQ(metrics::l_collision_rate(all, inner), 0.25);
  // The plain rate is the plain nearest-vertex test, as H-collision's.
  EXPECT_DOUBLE_EQ(metrics::l_collision_plain_rate(all, inner),
                   metrics::behind_share(all, g::Surface::from_mesh(inner)));
}

TEST(Metrics, CollisionRateNeedsVerticesAndValidFaces) {
  EXPECT_THROW(metrics::h_collision_rate(g::Points(0, 3), layers::test::unit_square_grid(3, 0.0f)), layers::Error);
  g::TriMesh bad = layers::test::unit_square_grid(3, 0.0f);
  bad.faces(0, 2) = 100;
  EXPECT_THROW(metrics::h_collision_rate(g::Points::Zero(1, 3), bad), layers::InputError);
}

TEST(Metrics, MeanStdOverSequences) {
  metrics::MeanStd s = metrics::mean_std({1.0, 2.0, 3.0, 4.0});
  EXPECT_DOUBLE_EQ(s.mean, 2.5);
  EXPECT_DOUBLE_EQ(s.std, std::sqrt(5.0 / 3.0));  // sample std: squares 5 over n - 1 = 3
  EXPECT_EQ(s.count, 4u);
  EXPECT_EQ(metrics::format(s), "2.5 +- 1.3");
  EXPECT_EQ(metrics::format(metrics::mean_std({611.25, 611.35}), 2), "611.30 +- 0.07");
  EXPECT_TRUE(std::isnan(metrics::mean_std({4.0}).std)) << "no spread is measured from one value";
  metrics::MeanStd empty = metrics::mean_std({});
  EXPECT_EQ(empty.count, 0u);
  EXPECT_EQ(empty.mean, 0.0);
  // Per-frame values -> per-sequence means -> mean +- std.
  double a = metrics::sequence_mean({2.0, 4.0}), b = metrics::sequence_mean({5.0, 7.0, 9.0});
  metrics::MeanStd over = metrics::mean_std({a, b});
  EXPECT_DOUBLE_EQ(over.mean, 5.0);
  EXPECT_DOUBLE_EQ(over.std, std::sqrt(8.0));
  EXPECT_THROW(metrics::sequence_mean({}), layers::Error);
}
