// The "static" reference model: a garment carried rigidly by the body root
// is reproduced exactly over a rollout; quaternion conventions; no
// parameters; errors.
#include <gtest/gtest.h>

#include <cmath>

#include "error_of.h"
#include "layers/core/config_node.h"
#include "layers/core/error.h"
#include "reference_fixture.h"
#include "spec.h"

namespace zoo = layers::zoo;
namespace cfg = layers::cfg;
namespace test = layers::test;
using layers::reference::make_static_model;

namespace {

// The root's pose at frame f: turning about a tilted axis and swaying
// about another while walking (the rotation axis changes over time, so the
// rotations of two frames do not commute).
test::Rigid root_pose(int f) {
  return test::rigid({0.2, 1.0, 0.3}, 0.15 * f + 0.02 * f * f, {0.05 * f, 0.9 + 0.01 * std::sin(f), -0.03 * f}) *
         test::rigid({1.0, 0.0, 0.1}, 0.4 * std::sin(0.5 * f), {0.0, 0.0, 0.0});
}

// Root rows [3,3] and quaternions [3,4] (w,x,y,z) of frames f-1, f, f+1.
at::Tensor roots(int f) {
  at::Tensor out = at::empty({3, 3});
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) out[i][k] = root_pose(f - 1 + i).translation()[k];
  return out;
}
at::Tensor root_rots(int f) {
  at::Tensor out = at::empty({3, 4});
  for (int i = 0; i < 3; ++i) {
    Eigen::Quaterniond q(root_pose(f - 1 + i).linear());
    out[i][0] = q.w(), out[i][1] = q.x(), out[i][2] = q.y(), out[i][3] = q.z();
  }
  return out;
}

// Garments and body in the root's frame (a jumpsuit front, a jacket over
// it, a patch of body).
struct Scene {
  at::Tensor inner = test::grid_points(4, 5, 0.05, {-0.1, -0.2, 0.12});
  at::Tensor outer = test::grid_points(5, 5, 0.06, {-0.12, -0.25, 0.16});
  at::Tensor body = test::grid_points(3, 3, 0.1, {-0.1, -0.1, 0.1});

  zoo::SequenceStatic sequence() const {
    zoo::SequenceStatic s;
    s.id = "rigid";
    s.body_faces = test::grid_faces_tensor(3, 3, at::kInt);
    s.garments = {test::grid_garment("jumpsuit", 0, inner, 4, 5), test::grid_garment("jacket", 1, outer, 5, 5)};
    return s;
  }
  // Everything at frame f.
  std::vector<at::Tensor> garments(int f) const {
    return {test::transformed(root_pose(f), inner), test::transformed(root_pose(f), outer)};
  }
  zoo::StepInput input(const std::vector<at::Tensor>& prev, const std::vector<at::Tensor>& current, int f) const {
    return test::step_input({{prev[0], current[0]}, {prev[1], current[1]}}, test::transformed(root_pose(f), body),
                            test::transformed(root_pose(f + 1), body), roots(f), root_rots(f));
  }
};

float max_abs_difference(const at::Tensor& a, const at::Tensor& b) { return (a - b).abs().max().item<float>(); }

}  // namespace

TEST(Static, ReproducesARigidlyCarriedGarmentOverARollout) {
  Scene scene;
  auto model = make_static_model(cfg::Node{});
  model->prepare(scene.sequence());
  std::vector<at::Tensor> prev = scene.garments(0), current = scene.garments(1);
  for (int f = 1; f <= 12; ++f) {
    zoo::StepOutput out = model->step(scene.input(prev, current, f));
    std::vector<at::Tensor> truth = scene.garments(f + 1);
    for (std::size_t k = 0; k < 2; ++k) {
      // The garment really moves (several cm per frame) ...
      ASSERT_GT(max_abs_difference(truth[k], current[k]), 0.02f) << "frame " << f;
      // ... and the model follows it exactly, fed its own predictions.
      EXPECT_LT(max_abs_difference(out.garments[k], truth[k]), 2e-5f) << "frame " << f << " garment " << k;
    }
    prev = current;
    current = out.garments;
  }
}

TEST(Static, UsesRowsTAndTPlusOneOnly) {
  // A garment off the root: with row t-1 garbage, the step from t to t+1
  // is still R(t+1) R(t)^T (p - root(t)) + root(t+1), checked by hand for a
  // quarter turn about y.
  Scene scene;
  auto model = make_static_model(cfg::Node{});
  model->prepare(scene.sequence());
  zoo::StepInput in = scene.input(scene.garments(0), scene.garments(1), 1);
  in.root = at::tensor({9.f, 9.f, 9.f, 1.f, 0.f, 0.f, 1.f, 2.f, 0.f}).reshape({3, 3});
  const float h = float(std::sqrt(0.5));
  in.root_rot = at::tensor({0.f, 0.f, 7.f, 0.f, 1.f, 0.f, 0.f, 0.f, h, 0.f, h, 0.f}).reshape({3, 4});
  in.garments[0].current = at::zeros_like(in.garments[0].current);
  in.garments[0].current.select(1, 0).fill_(2.0f);  // 1 m along +x from root(t)
  zoo::StepOutput out = model->step(in);
  // A quarter turn about +y maps +x to -z: (1, 2, 0) + (0, 0, -1).
  at::Tensor expected = at::tensor({1.f, 2.f, -1.f}).expand_as(in.garments[0].current);
  EXPECT_LT(max_abs_difference(out.garments[0], expected), 1e-6f);
}

TEST(Static, QuaternionLengthAndSignDoNotMatter) {
  Scene scene;
  auto model = make_static_model(cfg::Node{});
  model->prepare(scene.sequence());
  zoo::StepInput in = scene.input(scene.garments(2), scene.garments(3), 3);
  at::Tensor reference = model->step(in).garments[1];
  in.root_rot = in.root_rot * at::tensor({2.f, -0.5f, 3.f}).unsqueeze(1);
  EXPECT_LT(max_abs_difference(model->step(in).garments[1], reference), 1e-6f);
}

TEST(Static, HasNoParameters) {
  auto model = make_static_model(cfg::parse("{}", "static.yaml"));
  EXPECT_EQ(model->info().parameters, 0);
  EXPECT_EQ(model->info().trainable, 0);
  EXPECT_EQ(model->config().kind, cfg::Node::Kind::Map);
  EXPECT_TRUE(model->config().map.empty());
  std::string message =
      test::error_of<layers::InputError>([] { make_static_model(cfg::parse("{width: 3}", "static.yaml")); });
  EXPECT_NE(message.find("width"), std::string::npos) << message;
}

TEST(Static, ZeroQuaternionIsAnError) {
  Scene scene;
  auto model = make_static_model(cfg::Node{});
  model->prepare(scene.sequence());
  zoo::StepInput in = scene.input(scene.garments(0), scene.garments(1), 1);
  in.root_rot[2].zero_();
  std::string message = test::error_of<layers::Error>([&] { model->step(in); });
  EXPECT_NE(message.find("model 'static': step input root_rot: expected non-zero, finite quaternions"),
            std::string::npos)
      << message;
}
