// The metric registry: the built-in metrics in their order, what a frame
// scene gives each (per garment and for the scene), the registration
// rules, and the frame reductions.
#include <gtest/gtest.h>

#include <cmath>

#include "grid_mesh.h"
#include "layers/core/error.h"
#include "layers/metrics/registry.h"

namespace g = layers::geometry;
namespace metrics = layers::metrics;

namespace {

// A flat garment of n x n vertices at height z.
g::TriMesh sheet(int n, float z) { return layers::test::unit_square_grid(n, z); }

}  // namespace

TEST(MetricRegistry, BuiltInMetricsInTheirOrder) {
  // The first six, in the order every output lists them (a metric added
  // later goes after them).
  std::vector<std::string> keys;
  for (const metrics::MetricDef& d : metrics::registered()) keys.push_back(d.key);
  ASSERT_GE(keys.size(), 6u);
  keys.resize(6);
  EXPECT_EQ(keys, (std::vector<std::string>{"error_mm", "h_collision", "l_collision", "l_collision_plain", "h_crossing",
                                            "l_crossing"}));
  EXPECT_EQ(metrics::metric(metrics::kError).unit, metrics::Unit::Millimetre);
  EXPECT_EQ(metrics::metric(metrics::kError).diverged, metrics::Diverged::Bound);
  EXPECT_FALSE(metrics::metric(metrics::kError).truth);
  EXPECT_EQ(metrics::metric("l_crossing").scope, metrics::Scope::OuterLayer);
  for (const metrics::MetricDef& d : metrics::registered()) {
    EXPECT_FALSE(d.rule.empty()) << d.key;
    EXPECT_FALSE(d.description.empty()) << d.key;
    EXPECT_TRUE(d.compute) << d.key;
  }
  EXPECT_THROW(metrics::index_of("no_such_metric"), layers::Error);
}

TEST(MetricRegistry, FrameValuesOfAnInnerAndOuterGarmentOverABody) {
  // Body plane at z = 0; an inner sheet at z = 0.1 with 9 vertices, all in
  // front of the body; an outer sheet of 4 vertices at z = 0.05: behind the
  // inner garment's plane (the plain rule counts every one) and in front of
  // the body.
  const g::TriMesh body_mesh = sheet(11, 0.0f);
  const metrics::BodyFrame body(body_mesh);
  std::vector<g::TriMesh> garments = {sheet(3, 0.1f), sheet(2, 0.05f)};
  std::vector<g::Points> truth = {garments[0].vertices, garments[1].vertices};
  truth[1].col(2).array() += 0.002f;  // the outer garment 2 mm off: error 2 mm on 4 of 13 vertices
  const metrics::FrameScene scene(garments, {0, 1}, &truth, nullptr, &body);
  EXPECT_TRUE(scene.has_layers());

  const metrics::FrameValue error = metrics::metric("error_mm").compute(scene);
  ASSERT_EQ(error.garments.size(), 2u);
  EXPECT_NEAR(error.garments[0], 0.0, 1e-9);
  EXPECT_NEAR(error.garments[1], 2.0, 1e-3);
  EXPECT_NEAR(error.scene, 2.0 * 4.0 / 13.0, 1e-3);

  const metrics::FrameValue h = metrics::metric("h_collision").compute(scene);
  EXPECT_DOUBLE_EQ(h.scene, 0.0);

  const metrics::FrameValue plain = metrics::metric("l_collision_plain").compute(scene);
  EXPECT_DOUBLE_EQ(plain.scene, 1.0);
  ASSERT_EQ(plain.garments.size(), 2u);
  EXPECT_TRUE(std::isnan(plain.garments[0]));  // the inner garment has no L value
  EXPECT_DOUBLE_EQ(plain.garments[1], 1.0);
  // Ours: the outer sheet's vertices are nearest to the inner sheet's
  // corners, on its open edge: beside it, not behind.
  EXPECT_DOUBLE_EQ(metrics::metric("l_collision").compute(scene).scene, 0.0);

  // Without an inner garment the L metrics measure nothing.
  const metrics::FrameScene alone({garments[1]}, {1}, nullptr, nullptr, &body);
  EXPECT_TRUE(std::isnan(metrics::metric("l_collision").compute(alone).scene));
  EXPECT_TRUE(std::isnan(metrics::metric("l_crossing").compute(alone).scene));
  // The ground truth's scene has no truth to measure an error against.
  EXPECT_THROW(metrics::metric("error_mm").compute(alone), layers::Error);
}

TEST(MetricRegistry, AddedMetricsFollowTheBuiltInOnesAndLeave) {
  const std::size_t before = metrics::registered().size();
  {
    metrics::MetricDef d;
    d.key = "mean_height_mm";
    d.unit = metrics::Unit::Millimetre;
    d.frames = metrics::Reduce::Max;
    d.compute = [](const metrics::FrameScene& s) {
      return metrics::FrameValue{1000.0 * s.garment(0).vertices.col(1).cast<double>().mean(), {}};
    };
    metrics::ScopedMetric added(d);
    ASSERT_EQ(metrics::registered().size(), before + 1);
    EXPECT_EQ(metrics::registered().back().key, "mean_height_mm");
    EXPECT_EQ(metrics::registered().back().label, "mean_height_mm");  // the key when no label is given
    EXPECT_THROW(metrics::add(d), layers::Error);                     // taken
  }
  EXPECT_EQ(metrics::registered().size(), before);
  metrics::MetricDef bad;
  bad.key = "Bad Key";
  bad.compute = [](const metrics::FrameScene&) { return metrics::FrameValue{}; };
  EXPECT_THROW(metrics::add(bad), layers::Error);
  bad.key = "truth_x";
  EXPECT_THROW(metrics::add(bad), layers::Error);
  bad.key = "bound_share";
  bad.diverged = metrics::Diverged::Bound;  // the bound is in mm; this metric is a share
  EXPECT_THROW(metrics::add(bad), layers::Error);
  bad.diverged = metrics::Diverged::LeftOut;
  bad.key = "no_function";
  bad.compute = nullptr;
  EXPECT_THROW(metrics::add(bad), layers::Error);
  EXPECT_THROW(metrics::remove("h_collision"), layers::Error);  // built in
}

TEST(MetricRegistry, FramesReduceByTheMetricsRule) {
  const double nan = std::nan("");
  metrics::MetricDef mean, max;
  max.frames = metrics::Reduce::Max;
  EXPECT_DOUBLE_EQ(metrics::reduce_frames(mean, {1.0, nan, 3.0}), 2.0);  // left-out frames do not count
  EXPECT_DOUBLE_EQ(metrics::reduce_frames(max, {1.0, nan, 3.0, 2.0}), 3.0);
  EXPECT_TRUE(std::isnan(metrics::reduce_frames(mean, {nan, nan})));
  EXPECT_TRUE(std::isnan(metrics::reduce_frames(max, {})));
  const metrics::MeanStd spread = metrics::finite_mean_std({2.0, nan, 4.0});
  EXPECT_EQ(spread.count, 2u);
  EXPECT_DOUBLE_EQ(spread.mean, 3.0);
  EXPECT_EQ(metrics::format_value(metrics::metric("error_mm"), spread), "3.0 +- 1.4");  // sample std (n - 1)
  EXPECT_EQ(metrics::format_value(metrics::metric("h_collision"), {0.0125, 0.0, 3}), "1.25%");
  EXPECT_EQ(metrics::format_value(metrics::metric("h_collision"), {}), "-");
}
