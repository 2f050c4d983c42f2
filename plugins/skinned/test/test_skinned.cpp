// The "skinned" reference model against a synthetic two-joint arm: a
// garment skinned with the body's own weights is reproduced exactly over a
// rollout; blended weights match the formula; the binding is made once per
// prepared sequence; errors.
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
using layers::reference::make_skinned_model;

namespace {

constexpr int kRows = 3, kCols = 13;  // the arm: 3 x 13 vertices, 5 cm apart, along +x
const Eigen::Vector3d kElbow(0.3, 0.0, 0.0);

// Joint j's world transform at frame f, as the map from the rest pose
// (x -> R (x - rest_joint) + p) written as an isometry. The shoulder turns
// and moves the whole arm; the elbow bends (bend = true) or the forearm
// slides along (bend = false: same rotation for both joints, only the
// translations differ).
test::Rigid joint_motion(int j, int f, bool bend) {
  const test::Rigid shoulder = test::rigid({0.0, 1.0, 0.2}, 0.1 * f, {0.02 * f, 0.01 * std::sin(f), 0.0});
  if (j == 0) return shoulder;
  test::Rigid local = test::Rigid::Identity();
  if (bend) {
    local = test::rigid({0.0, 0.0, 1.0}, 0.2 * f, kElbow) * test::Rigid(Eigen::Translation3d(-kElbow));
  } else {
    local.translation() = Eigen::Vector3d(0.01 * f, 0.005 * f, -0.004 * f);
  }
  return shoulder * local;
}

// StepInput::joints at frame f: [2,3,4] rows [R | p], p = where the rest
// joint went.
at::Tensor joints(int f, bool bend) {
  at::Tensor out = at::empty({2, 3, 4});
  for (int j = 0; j < 2; ++j) {
    const test::Rigid g = joint_motion(j, f, bend);
    const Eigen::Vector3d rest_joint = j == 0 ? Eigen::Vector3d::Zero() : kElbow;
    const Eigen::Vector3d p = g * rest_joint;
    for (int r = 0; r < 3; ++r) {
      for (int c = 0; c < 3; ++c) out[j][r][c] = g.linear()(r, c);
      out[j][r][3] = p[r];
    }
  }
  return out;
}

// Skinning data of the arm: blended (weight of the forearm growing along
// x) or one-hot (upper arm / forearm split at the elbow). Joint slots 2
// and 3 carry zero weight.
struct Skin {
  at::Tensor index, weight;
};
Skin arm_skin(bool blended) {
  at::Tensor x = test::grid_points(kRows, kCols, 0.05, {0, 0, 0}).select(1, 0);
  at::Tensor forearm = blended ? (x / 0.6).clamp(0, 1) : (x >= 0.3 - 1e-6).to(at::kFloat);
  Skin s;
  s.index = at::tensor({0, 1, 0, 1}, at::kInt).repeat({x.size(0), 1});
  s.weight = at::stack({1 - forearm, forearm, at::zeros_like(x), at::zeros_like(x)}, 1);
  return s;
}

// Linear blend skinning of rest points [N,3] (each with the weights of
// the arm vertex it sits on) at frame f.
at::Tensor skinned(const at::Tensor& rest, const Skin& skin, int f, bool bend) {
  at::Tensor w = skin.weight.to(at::kDouble);
  return (w.select(1, 0).unsqueeze(1) * test::transformed(joint_motion(0, f, bend), rest.to(at::kDouble)) +
          w.select(1, 1).unsqueeze(1) * test::transformed(joint_motion(1, f, bend), rest.to(at::kDouble)))
      .to(at::kFloat);
}

struct Arm {
  bool bend;
  Skin skin;
  at::Tensor body_rest = test::grid_points(kRows, kCols, 0.05, {0, 0, 0});
  // The sleeve sits on the arm, 4 mm above each arm vertex.
  at::Tensor sleeve_rest = test::grid_points(kRows, kCols, 0.05, {0, 0, 0.004});

  Arm(bool bend_, bool blended) : bend(bend_), skin(arm_skin(blended)) {}

  zoo::SequenceStatic sequence(const std::string& id = "arm") const {
    zoo::SequenceStatic s;
    s.id = id;
    s.body_faces = test::grid_faces_tensor(kRows, kCols, at::kInt);
    s.garments = {test::grid_garment("sleeve", 0, sleeve_rest, kRows, kCols)};
    s.skin_index = skin.index;
    s.skin_weight = skin.weight;
    return s;
  }
  at::Tensor body(int f) const { return skinned(body_rest, skin, f, bend); }
  at::Tensor sleeve(int f) const { return skinned(sleeve_rest, skin, f, bend); }
  zoo::StepInput input(const at::Tensor& prev, const at::Tensor& current, int f) const {
    at::Tensor root = at::zeros({3, 3}), rot = at::zeros({3, 4});
    rot.select(1, 0).fill_(1.0f);
    return test::step_input({{prev, current}}, body(f), body(f + 1), root, rot, joints(f, bend), joints(f + 1, bend));
  }
};

float max_abs_difference(const at::Tensor& a, const at::Tensor& b) { return (a - b).abs().max().item<float>(); }

// Rolls the model out from frames 0 and 1 and returns the largest error
// against the skinned sleeve over frames 2 .. frames.
float rollout_error(const Arm& arm, int frames) {
  auto model = make_skinned_model(cfg::Node{});
  model->prepare(arm.sequence());
  at::Tensor prev = arm.sleeve(0), current = arm.sleeve(1);
  float worst = 0.0f;
  for (int f = 1; f < frames; ++f) {
    at::Tensor next = model->step(arm.input(prev, current, f)).garments[0];
    EXPECT_GT(max_abs_difference(arm.sleeve(f + 1), current), 0.01f) << "the sleeve should move, frame " << f;
    worst = std::max(worst, max_abs_difference(next, arm.sleeve(f + 1)));
    prev = current;
    current = next;
  }
  return worst;
}

}  // namespace

TEST(Skinned, ReproducesASleeveSkinnedToABendingArm) {
  EXPECT_LT(rollout_error(Arm(/*bend=*/true, /*blended=*/false), 12), 2e-5f);
}

TEST(Skinned, ReproducesBlendedWeightsWhenJointsShareTheirRotation) {
  // With a common rotation, blending the per-frame motions is exactly
  // blending the poses, so the rollout is exact for blended weights too.
  EXPECT_LT(rollout_error(Arm(/*bend=*/false, /*blended=*/true), 12), 2e-5f);
}

TEST(Skinned, BlendsTheJointMotionsWithNormalisedWeights) {
  // Blended weights, bending elbow: one step against the formula evaluated
  // per vertex in double precision. The stored weights sum to 2: the model
  // renormalises them.
  Arm arm(/*bend=*/true, /*blended=*/true);
  zoo::SequenceStatic s = arm.sequence();
  s.skin_weight = s.skin_weight * 2.0f;
  auto model = make_skinned_model(cfg::Node{});
  model->prepare(s);
  const int f = 4;
  at::Tensor current = arm.sleeve(f);
  at::Tensor got = model->step(arm.input(arm.sleeve(f - 1), current, f)).garments[0];

  at::Tensor expected = at::zeros({current.size(0), 3}, at::kDouble);
  for (int j = 0; j < 2; ++j) {
    const test::Rigid step = joint_motion(j, f + 1, true) * joint_motion(j, f, true).inverse();
    expected +=
        arm.skin.weight.select(1, j).to(at::kDouble).unsqueeze(1) * test::transformed(step, current.to(at::kDouble));
  }
  EXPECT_LT(max_abs_difference(got, expected.to(at::kFloat)), 1e-5f);
  // Not merely one joint's motion.
  for (int j = 0; j < 2; ++j)
    EXPECT_GT(max_abs_difference(
                  got, test::transformed(joint_motion(j, f + 1, true) * joint_motion(j, f, true).inverse(), current)),
              1e-3f);
}

TEST(Skinned, BindsOncePerPreparedSequence) {
  // One-hot arm: a sleeve vertex on an upper-arm vertex binds to the
  // shoulder at the first step; later it follows the shoulder even when
  // it lies on the forearm, until the sequence is derived afresh.
  Arm arm(/*bend=*/true, /*blended=*/false);
  const int f = 5;
  at::Tensor on_forearm = arm.sleeve(f);  // every sleeve vertex on its own arm vertex at f
  at::Tensor shifted = on_forearm.clone();
  // Sleeve vertex 0 (upper arm) placed onto the forearm's tip (vertex kCols-1).
  shifted[0] = on_forearm[kCols - 1];
  const at::Tensor tip = shifted[0].unsqueeze(0);
  auto shoulder_step = joint_motion(0, f + 1, true) * joint_motion(0, f, true).inverse();
  auto elbow_step = joint_motion(1, f + 1, true) * joint_motion(1, f, true).inverse();
  const at::Tensor by_shoulder = test::transformed(shoulder_step, tip)[0];
  const at::Tensor by_elbow = test::transformed(elbow_step, tip)[0];
  ASSERT_GT(max_abs_difference(by_shoulder, by_elbow), 0.01f);

  auto model = make_skinned_model(cfg::Node{});
  model->set_cache_capacity(1);
  model->prepare(arm.sequence("a"));
  model->step(arm.input(arm.sleeve(f - 1), on_forearm, f));  // binds: vertex 0 -> shoulder
  EXPECT_LT(max_abs_difference(model->step(arm.input(on_forearm, shifted, f)).garments[0][0], by_shoulder), 1e-5f);

  // Still bound after another sequence was prepared and stepped (if cached).
  model->set_cache_capacity(2);
  model->prepare(arm.sequence("b"));
  EXPECT_LT(max_abs_difference(model->step(arm.input(on_forearm, shifted, f)).garments[0][0], by_elbow), 1e-5f);
  model->prepare(arm.sequence("a"));
  EXPECT_LT(max_abs_difference(model->step(arm.input(on_forearm, shifted, f)).garments[0][0], by_shoulder), 1e-5f);

  // Evicted from the cache: preparing "a" again binds afresh.
  model->set_cache_capacity(1);
  model->prepare(arm.sequence("c"));
  model->prepare(arm.sequence("a"));
  EXPECT_LT(max_abs_difference(model->step(arm.input(on_forearm, shifted, f)).garments[0][0], by_elbow), 1e-5f);

  // Deterministic: fresh models stepped the same way agree bit for bit.
  auto fresh = [&] {
    auto m = make_skinned_model(cfg::Node{});
    m->prepare(arm.sequence("a"));
    m->step(arm.input(arm.sleeve(f - 1), on_forearm, f));
    return m->step(arm.input(on_forearm, shifted, f)).garments[0];
  };
  EXPECT_TRUE(at::equal(fresh(), fresh()));
}

TEST(Skinned, HasNoParameters) {
  auto model = make_skinned_model(cfg::parse("{}", "skinned.yaml"));
  EXPECT_EQ(model->info().parameters, 0);
  EXPECT_TRUE(model->config().map.empty());
  std::string message =
      test::error_of<layers::InputError>([] { make_skinned_model(cfg::parse("{radius: 1}", "skinned.yaml")); });
  EXPECT_NE(message.find("radius"), std::string::npos) << message;
}

TEST(Skinned, MissingJointsAreAClearError) {
  Arm arm(true, false);
  auto model = make_skinned_model(cfg::Node{});
  model->prepare(arm.sequence());
  zoo::StepInput in = arm.input(arm.sleeve(0), arm.sleeve(1), 1);
  in.joints_next = at::Tensor();
  std::string message = test::error_of<layers::Error>([&] { model->step(in); });
  EXPECT_NE(message.find("model 'skinned': step input joints / joints_next: expected the joint transforms [J,3,4] "
                         "at t and t+1 (LAYERS-H5 body/joints), got no joints_next"),
            std::string::npos)
      << message;
  in.joints = at::Tensor();
  message = test::error_of<layers::Error>([&] { model->step(in); });
  EXPECT_NE(message.find("got no joints"), std::string::npos) << message;
}

TEST(Skinned, MissingSkinningDataIsAnInputError) {
  Arm arm(true, false);
  zoo::SequenceStatic s = arm.sequence();
  s.skin_index = at::Tensor();
  s.skin_weight = at::Tensor();
  auto model = make_skinned_model(cfg::Node{});
  std::string message = test::error_of<layers::InputError>([&] { model->prepare(s); });
  EXPECT_NE(message.find("sequence 'arm'"), std::string::npos) << message;
  EXPECT_NE(message.find("skin_index"), std::string::npos) << message;
}

TEST(Skinned, TooFewJointsForTheWeightsIsAnError) {
  Arm arm(true, false);
  zoo::SequenceStatic s = arm.sequence();
  s.skin_index = s.skin_index.clone();
  s.skin_index.select(1, 1).fill_(5);  // names joint 5 (with weight 0); no joint_parents to catch it
  auto model = make_skinned_model(cfg::Node{});
  model->prepare(s);
  std::string message = test::error_of<layers::Error>([&] { model->step(arm.input(arm.sleeve(0), arm.sleeve(1), 1)); });
  EXPECT_NE(message.find("expected at least 6 joints"), std::string::npos) << message;
}

TEST(Skinned, ZeroWeightsAreAnInputError) {
  Arm arm(true, false);
  zoo::SequenceStatic s = arm.sequence();
  s.skin_weight = at::zeros_like(s.skin_weight);
  auto model = make_skinned_model(cfg::Node{});
  model->prepare(s);
  std::string message =
      test::error_of<layers::InputError>([&] { model->step(arm.input(arm.sleeve(0), arm.sleeve(1), 1)); });
  EXPECT_NE(message.find("skin_weight"), std::string::npos) << message;
}

TEST(Skinned, FollowsTheModelToAnotherDevice) {
  // No parameters, but the model moves with to(device) and runs there.
  if (!at::hasCUDA()) GTEST_SKIP() << "no CUDA device in this build";
  Arm arm(true, true);
  auto cpu = make_skinned_model(cfg::Node{});
  cpu->prepare(arm.sequence());
  zoo::StepInput in = arm.input(arm.sleeve(2), arm.sleeve(3), 3);
  at::Tensor expected = cpu->step(in).garments[0];

  auto gpu = make_skinned_model(cfg::Node{});
  gpu->to(at::kCUDA);
  gpu->prepare(arm.sequence());
  for (zoo::GarmentState& g : in.garments) g = {g.prev.to(at::kCUDA), g.current.to(at::kCUDA)};
  for (at::Tensor* t : {&in.body, &in.body_next, &in.root, &in.root_rot, &in.wind_rotation, &in.wind_strength,
                        &in.joints, &in.joints_next})
    *t = t->to(at::kCUDA);
  at::Tensor got = gpu->step(in).garments[0];
  EXPECT_TRUE(got.is_cuda());
  EXPECT_LT(max_abs_difference(got.cpu(), expected), 1e-5f);
}
