// The LayersNet model on synthetic layered scenes: shapes and counts of a
// forward pass, any number of garments, body vertices far from the
// garment change nothing, the heading frame turns the prediction, the
// body and bones integration bases add exactly their motion, a learned
// blend mixes inertia and bones by its gate, parameters
// and static data are checked, the
// plugin registers it, and it overfits one window.
#include <gtest/gtest.h>

#include <functional>
#include <iostream>

#include <torch/optim/adam.h>

#include "joint_binding.h"
#include "layers/core/config_node.h"
#include "layers/core/error.h"
#include "layers/zoo/plugin_loader.h"
#include "layers/zoo/registry.h"
#include "layers/zoo/rotations.h"
#include "layers/zoo/skinning.h"
#include "layersnet.h"
#include "synthetic_scene.h"
#include "topology.h"

namespace ln = layers::layersnet;
namespace zoo = layers::zoo;
namespace cfg = layers::cfg;

namespace {

std::shared_ptr<ln::LayersNet> make(const std::string& yaml = "{}") {
  return std::dynamic_pointer_cast<ln::LayersNet>(ln::make_layersnet(cfg::parse(yaml, "params.yaml")));
}

double position_mse(const std::vector<at::Tensor>& pred, const std::vector<at::Tensor>& truth) {
  double sum = 0;
  std::int64_t n = 0;
  for (std::size_t k = 0; k < pred.size(); ++k) {
    sum += (pred[k] - truth[k]).pow(2).sum(1).sum().item<double>();
    n += pred[k].size(0);
  }
  return sum / static_cast<double>(n);
}

zoo::StepInput with_far_body(zoo::StepInput in, std::int64_t extra) {
  const at::Tensor far = at::rand({extra, 3}) + at::tensor({10.0f, 10.0f, -10.0f});
  in.body = at::cat({in.body, far});
  in.body_next = at::cat({in.body_next, far + 0.01f});
  return in;
}

// [1,4] quaternion of `yaw` radians about +y.
at::Tensor yaw_quaternion(double yaw) {
  return at::tensor({std::cos(yaw / 2), 0.0, std::sin(yaw / 2), 0.0}, at::kFloat).unsqueeze(0);
}

// The whole step turned by `yaw` about +y (around the world origin) and
// moved by `shift`: garments, body, root, root and wind rotations.
zoo::StepInput turned(zoo::StepInput in, double yaw, const at::Tensor& shift) {
  const at::Tensor q = yaw_quaternion(yaw);
  const at::Tensor r = zoo::rotation_matrices(q)[0];
  auto move = [&](const at::Tensor& p) { return at::matmul(p, r.t()) + shift; };
  for (zoo::GarmentState& g : in.garments) g = {move(g.prev), move(g.current)};
  in.body = move(in.body);
  in.body_next = move(in.body_next);
  in.root = move(in.root);
  in.root_rot = zoo::quaternion_multiply(q.expand({3, 4}), in.root_rot);
  in.wind_rotation = zoo::quaternion_multiply(q.expand({2, 4}), in.wind_rotation);
  return in;
}

}  // namespace

TEST(LayersNet, TopologyJoinsGarmentsInOneIndexSpace) {
  ln::testing::SceneSize size;
  size.garment_rows = 6;
  size.garment_cols = 12;
  size.garments = 3;
  auto scene = ln::testing::make_scene(size);
  scene.statics.garments[2].attributes = scene.statics.garments[0].attributes.clone();
  const ln::SceneTopology t = ln::build_topology(scene.statics, 0.1);
  EXPECT_EQ(t.vertex_offset, (std::vector<std::int64_t>{0, 72, 144, 216}));
  ASSERT_EQ(t.patch_offset.size(), 4u);
  const std::int64_t P = t.patches();

  // Means: of a constant, the constant; of the vertex index, within the
  // patch's index range; back to vertices, a mean of patch means.
  const at::Tensor ones = at::ones({t.vertices(), 1});
  EXPECT_TRUE(at::allclose(ln::patch_mean(t, ones), at::ones({P, 1})));
  EXPECT_TRUE(at::allclose(ln::vertex_mean(t, at::ones({P, 2})), at::ones({t.vertices(), 2})));
  const at::Tensor index = at::arange(t.vertices(), at::kFloat).unsqueeze(1);
  const at::Tensor mean_index = ln::patch_mean(t, index).squeeze(1);
  for (std::size_t k = 0; k < 3; ++k) {
    const at::Tensor m = mean_index.narrow(0, t.patch_offset[k], t.patch_offset[k + 1] - t.patch_offset[k]);
    EXPECT_GE(m.min().item<float>(), static_cast<float>(t.vertex_offset[k]));
    EXPECT_LE(m.max().item<float>(), static_cast<float>(t.vertex_offset[k + 1] - 1));
  }

  // E^M: symmetric, no self edges, never across garments.
  EXPECT_TRUE(at::equal(t.mesh_mask, t.mesh_mask.t()));
  EXPECT_FALSE(t.mesh_mask.diagonal().any().item<bool>());
  EXPECT_EQ(t.mesh_mask.sum().item<std::int64_t>(), 2 * t.mesh_edges);
  const std::int64_t p1 = t.patch_offset[1];
  EXPECT_FALSE(t.mesh_mask.narrow(0, 0, p1).narrow(1, p1, P - p1).any().item<bool>());

  // Garments 0 and 2 share their attribute token; garment 1 has its own.
  ASSERT_EQ(t.attributes.size(0), 2);
  EXPECT_TRUE(t.patch_attribute.narrow(0, 0, p1).select(1, 0).all().item<bool>());
  EXPECT_TRUE(t.patch_attribute.narrow(0, t.patch_offset[2], P - t.patch_offset[2]).select(1, 0).all().item<bool>());
  EXPECT_EQ(t.patch_attribute.sum().item<std::int64_t>(), P);
  // Kinds: garment 0 inner, the others outer (synthetic layers 0, 1, 1).
  EXPECT_EQ(t.patch_kind.select(1, 0).sum().item<float>(), static_cast<float>(p1));
  // Min-max scaling: mass 0.3 in [0.2, 0.8] -> 1/6.
  EXPECT_NEAR(t.attributes[0][0].item<float>(), 1.0f / 6, 1e-6);
}

TEST(LayersNet, ForwardPassOnTwoGarments) {
  at::manual_seed(0);
  const auto scene = ln::testing::make_scene({});
  auto model = make();
  model->set_normalization(ln::testing::scene_normalization(scene));
  model->prepare(scene.statics);

  // t = 5: wind blows (second half); t = 1: calm.
  for (std::int64_t t : {5, 1}) {
    const zoo::StepOutput out = model->step(scene.input(t));
    ASSERT_EQ(out.garments.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      EXPECT_EQ(out.garments[k].sizes(), scene.garments[k][t].sizes());
      EXPECT_TRUE(at::isfinite(out.garments[k]).all().item<bool>());
      // An untrained model still moves the garment by a bounded amount.
      EXPECT_LT((out.garments[k] - scene.garments[k][t]).abs().max().item<double>(), 1.0);
    }
    const ln::StepCounts& c = model->last_counts();
    EXPECT_EQ(c.vertices, 320);
    EXPECT_GT(c.patches, 20);
    EXPECT_LT(c.patches, 160);
    // gravity, wind while it blows, one token per distinct attribute vector
    EXPECT_EQ(c.abstract_tokens, t == 5 ? 4 : 3);
    EXPECT_GT(c.mesh_edges, c.patches);
    EXPECT_GT(c.world_edges, 0);  // the layers are 2.5 cm apart
    EXPECT_GT(c.body_tokens, 0);
    EXPECT_LE(c.body_tokens, 288);
    EXPECT_LE(c.body_edges, 16 * c.patches);
    EXPECT_GE(c.body_edges, c.body_tokens);
    EXPECT_EQ(model->step_counters().at("patches"), static_cast<double>(c.patches));
    EXPECT_EQ(model->step_counters().at("body_tokens"), static_cast<double>(c.body_tokens));
  }
}

TEST(LayersNet, BodyVerticesFarFromTheGarmentChangeNothing) {
  at::manual_seed(1);
  const auto scene = ln::testing::make_scene({});
  auto model = make("{width: 32, blocks: 2, heads: 4}");
  model->set_normalization(ln::testing::scene_normalization(scene));
  model->prepare(scene.statics);
  const zoo::StepOutput base = model->step(scene.input(5));
  const ln::StepCounts counts = model->last_counts();
  const zoo::StepOutput more = model->step(with_far_body(scene.input(5), 1000));
  for (std::size_t k = 0; k < base.garments.size(); ++k)
    EXPECT_TRUE(at::equal(base.garments[k], more.garments[k])) << "garment " << k;
  EXPECT_EQ(model->last_counts().body_tokens, counts.body_tokens);
  EXPECT_EQ(model->last_counts().body_edges, counts.body_edges);

  // Moving the body away from the garment does change the prediction.
  zoo::StepInput moved = scene.input(5);
  moved.body_next = moved.body_next + at::tensor({0.0f, 0.0f, 0.5f});
  const zoo::StepOutput other = model->step(moved);
  EXPECT_FALSE(at::allclose(base.garments[0], other.garments[0]));
  EXPECT_EQ(model->last_counts().body_tokens, 0);
}

TEST(LayersNet, HeadingFrameTurnsThePredictionWithTheBody) {
  at::manual_seed(4);
  const auto scene = ln::testing::make_scene({});
  zoo::StepInput in = scene.input(5);  // the wind blows
  // The root already faces somewhere, leaning a little forward.
  in.root_rot = at::tensor({0.95f, 0.1f, 0.29f, 0.0f}).repeat({3, 1});
  const double yaw = 1.1;
  const at::Tensor shift = at::tensor({0.7f, 0.0f, -1.3f});
  const at::Tensor r = zoo::rotation_matrices(yaw_quaternion(yaw))[0];
  for (const bool heading : {true, false}) {
    auto model =
        make(heading ? "{width: 32, blocks: 2, heads: 4, heading_frame: true}" : "{width: 32, blocks: 2, heads: 4}");
    model->set_normalization(ln::testing::scene_normalization(scene));
    model->prepare(scene.statics);
    const zoo::StepOutput base = model->step(in), other = model->step(turned(in, yaw, shift));
    const zoo::StepOutput moved = model->step(turned(in, 0.0, shift));
    for (std::size_t k = 0; k < base.garments.size(); ++k) {
      // Translation never matters; turning matters only without the heading frame.
      EXPECT_TRUE(at::allclose(moved.garments[k], base.garments[k] + shift, 1e-5, 1e-5)) << k;
      const double off = (other.garments[k] - (at::matmul(base.garments[k], r.t()) + shift)).abs().max().item<double>();
      std::cout << (heading ? "heading" : "world") << " garment " << k << ": " << off
                << " m off the turned prediction\n";
      if (heading)
        EXPECT_LT(off, 1e-5) << "garment " << k;
      else
        EXPECT_GT(off, 1e-4) << "garment " << k;
    }
  }
}

namespace {

constexpr double kBaseRadius = 0.05;  // body_radius of the base tests: some vertices in range, some not

// Garment k's velocity t-1 -> t relative to the root (the inertial base).
at::Tensor root_velocity(const zoo::StepInput& in, std::size_t k) {
  return (in.garments[k].current - in.root[1]) - (in.garments[k].prev - in.root[0]);
}

// Steps `in` with two models of the same weights, the inertial base and
// `base`, and checks that they differ by exactly (follow(k) - garment
// velocity) where the garment vertex has a next-frame body vertex within
// the radius and not at all elsewhere (no heading frame: root-relative
// world axes). follow(k, x) is the base's displacement of garment k's
// vertices x from t to t+1 in that frame.
void expect_base_adds(const ln::testing::SyntheticScene& scene, const zoo::StepInput& in, const std::string& base,
                      const std::function<at::Tensor(std::size_t, const at::Tensor&)>& follow) {
  const std::string shape = "{width: 32, blocks: 2, heads: 4, body_radius: " + std::to_string(kBaseRadius);
  at::manual_seed(5);
  auto inertial = make(shape + "}");
  at::manual_seed(5);
  auto other = make(shape + ", base: " + base + "}");
  for (auto& m : {inertial, other}) {
    m->set_normalization(ln::testing::scene_normalization(scene));
    m->prepare(scene.statics);
  }
  const zoo::StepOutput a = inertial->step(in), b = other->step(in);
  std::int64_t near_count = 0, far_count = 0;
  for (std::size_t k = 0; k < a.garments.size(); ++k) {
    const at::Tensor x = in.garments[k].current;
    const at::Tensor valid = (std::get<0>(at::cdist(x, in.body_next).min(1)) < kBaseRadius).unsqueeze(1);
    const at::Tensor moved = follow(k, x) - root_velocity(in, k);
    // The bases differ somewhere (the body does not move with the garment).
    EXPECT_GT(moved.abs().max().item<double>(), 1e-4) << base << " garment " << k;
    const at::Tensor expected = at::where(valid, moved, at::zeros_like(moved));
    EXPECT_TRUE(at::allclose(b.garments[k] - a.garments[k], expected, 1e-5, 1e-6)) << base << " garment " << k;
    near_count += valid.sum().item<std::int64_t>();
    far_count += valid.logical_not().sum().item<std::int64_t>();
  }
  std::cout << base << " base: " << near_count << " vertices in range, " << far_count << " keep their velocity\n";
  EXPECT_GT(near_count, 0);
  EXPECT_GT(far_count, 0);
}

// [R|p] of a skeleton turned by `yaw` about +y and moved by `shift` from
// its T-pose joint positions `rest` [J,3] (identity rotations): [J,3,4].
at::Tensor posed_joints(const at::Tensor& rest, double yaw, const at::Tensor& shift) {
  const at::Tensor r = zoo::rotation_matrices(yaw_quaternion(yaw))[0];
  const std::int64_t n = rest.size(0);
  return at::cat({r.expand({n, 3, 3}), (at::matmul(rest, r.t()) + shift).unsqueeze(2)}, 2);
}

// A three-joint spine along the synthetic body's axis (bone 0 -> 1 runs
// through the garments, bone 1 -> 2 above them) as the scene's skeleton;
// returns its T-pose joint positions [3,3].
at::Tensor add_spine(ln::testing::SyntheticScene& scene) {
  const at::Tensor rest = at::tensor({0.0f, -0.4f, 0.0f, 0.0f, 0.4f, 0.0f, 0.0f, 1.2f, 0.0f}).view({3, 3});
  scene.statics.joint_parents = at::tensor({-1, 0, 1}, at::kLong);
  scene.statics.tpose_joints = posed_joints(rest, 0.0, at::zeros({3}));
  return rest;
}

// Step 5 of the scene with the whole spine turning about +y by 0.1 rad
// and moving with the root: every bound vertex is carried rigidly.
zoo::StepInput turning_spine_step(const ln::testing::SyntheticScene& scene, const at::Tensor& rest) {
  zoo::StepInput in = scene.input(5);
  in.joints = posed_joints(rest, 0.3, in.root[1]);
  in.joints_next = posed_joints(rest, 0.4, in.root[2]);
  return in;
}

// That rigid turn's root-relative displacement of points x from t to t+1.
at::Tensor spine_turn(const zoo::StepInput& in, const at::Tensor& x) {
  const at::Tensor turn = zoo::rotation_matrices(yaw_quaternion(0.1))[0];
  return at::matmul(x - in.root[1], turn.t()) - (x - in.root[1]);
}

// prepare() rejects `statics` with an InputError naming `field`.
void expect_prepare_error(zoo::Model& model, const zoo::SequenceStatic& statics, const std::string& field) {
  try {
    model.prepare(statics);
    FAIL() << "no error";
  } catch (const layers::InputError& e) {
    EXPECT_EQ(e.field(), field);
  }
}

}  // namespace

TEST(LayersNet, BodyBaseFollowsTheNearestBodyVertexWithinTheRadius) {
  const auto scene = ln::testing::make_scene({});
  const zoo::StepInput in = scene.input(5);
  // The nearest next-frame body vertex's displacement, root-relative.
  expect_base_adds(scene, in, "body", [&](std::size_t, const at::Tensor& x) {
    const at::Tensor nearest = std::get<1>(at::cdist(x, in.body_next).min(1));
    return (in.body_next.index_select(0, nearest) - in.root[2]) - (in.body.index_select(0, nearest) - in.root[1]);
  });
  EXPECT_THROW(make("{base: wind}"), layers::InputError);
}

TEST(LayersNet, BonesBaseCarriesTheGarmentWithItsRestPoseBones) {
  auto scene = ln::testing::make_scene({}, "bones");
  const at::Tensor rest = add_spine(scene);
  const zoo::StepInput in = turning_spine_step(scene, rest);
  expect_base_adds(scene, in, "bones", [&](std::size_t, const at::Tensor& x) { return spine_turn(in, x); });

  // The binding: every garment vertex on bone 0 -> 1 (moved by joint 0).
  const ln::JointBinding binding = ln::bind_to_bones(scene.statics);
  EXPECT_TRUE(binding.joint.select(1, 0).eq(0).all().item<bool>());
  EXPECT_GT(binding.weight.select(1, 0).min().item<float>(), 0.99f);
  EXPECT_TRUE(at::allclose(binding.weight.sum(1), at::ones({binding.weight.size(0)})));

  // No skeleton: a clear error at prepare; no joints in the step: an error.
  auto bones = make("{width: 16, blocks: 1, heads: 2, base: bones}");
  scene.statics.id = "no-skeleton";
  scene.statics.tpose_joints = at::Tensor();
  expect_prepare_error(*bones, scene.statics, "tpose_joints");
  scene.statics.id = "bones-again";
  scene.statics.tpose_joints = posed_joints(rest, 0.0, at::zeros({3}));
  bones->prepare(scene.statics);
  EXPECT_THROW(bones->step(scene.input(5)), layers::Error);
}

TEST(LayersNet, SkinBaseCarriesTheGarmentWithItsNearestBodyVertexsSkinning) {
  auto scene = ln::testing::make_scene({}, "skin");
  const at::Tensor rest = add_spine(scene);
  // Skinning of the body's rest cylinder (its T-pose): joint 0 at the
  // bottom, joint 1 at the top, blended linearly in between.
  const at::Tensor body_tpose = scene.body[0] - scene.root[0];
  const at::Tensor up = ((body_tpose.select(1, 1) + 0.4f) / 0.8f).clamp(0, 1);
  const at::Tensor none = at::zeros_like(up);
  scene.statics.skin_index = at::tensor({0, 1, 2, 2}, at::kLong).repeat({body_tpose.size(0), 1});
  scene.statics.skin_weight = at::stack({1 - up, up, none, none}, 1);
  // A bending pose (joint 1 turns further than joint 0, so the rotations
  // blend), and the body skinned into it at t and t+1.
  const auto bent = [&](double yaw0, double yaw1, const at::Tensor& shift) {
    at::Tensor j = posed_joints(rest, yaw0, shift);
    j[1].copy_(posed_joints(rest, yaw1, shift)[1]);
    return j;
  };
  const auto skinned = [&](const at::Tensor& joints) {
    return zoo::move_with_joints(zoo::joint_steps(scene.statics.tpose_joints, joints), body_tpose,
                                 scene.statics.skin_index, scene.statics.skin_weight);
  };
  zoo::StepInput in = scene.input(5);
  in.joints = bent(0.3, 0.6, in.root[1]);
  in.joints_next = bent(0.4, 0.8, in.root[2]);
  in.body = skinned(in.joints);
  in.body_next = skinned(in.joints_next);

  // Expected: each garment vertex takes the weights of the T-pose body
  // vertex nearest its rest position and moves with them from t to t+1.
  std::vector<at::Tensor> joint, weight;
  for (const zoo::GarmentStatic& g : scene.statics.garments) {
    const at::Tensor nearest = std::get<1>(at::cdist(g.rest, body_tpose).min(1));
    joint.push_back(scene.statics.skin_index.index_select(0, nearest));
    weight.push_back(scene.statics.skin_weight.index_select(0, nearest));
  }
  const ln::JointBinding binding = ln::bind_to_skin(scene.statics, in.body, in.joints);
  EXPECT_TRUE(at::allclose(binding.weight, at::cat(weight), 1e-5, 1e-6));
  EXPECT_GT(at::cat(weight).select(1, 1).std().item<double>(), 0.1);  // the weights vary along the garment
  const zoo::JointSteps steps = zoo::joint_steps(in.joints, in.joints_next);
  expect_base_adds(scene, in, "skin", [&](std::size_t k, const at::Tensor& x) {
    return (zoo::move_with_joints(steps, x, joint[k], weight[k]) - in.root[2]) - (x - in.root[1]);
  });

  // No skinning data: a clear error when the sequence is prepared.
  auto skin = make("{width: 16, blocks: 1, heads: 2, base: skin}");
  scene.statics.id = "no-skin";
  scene.statics.skin_weight = at::Tensor();
  expect_prepare_error(*skin, scene.statics, "skin_weight");
}

TEST(LayersNet, LearnedBlendMixesInertiaAndBonesByTheDecodersGate) {
  auto scene = ln::testing::make_scene({}, "blend");
  const at::Tensor rest = add_spine(scene);
  const zoo::StepInput in = turning_spine_step(scene, rest);
  const std::string shape = "{width: 32, blocks: 2, heads: 4";
  auto inertial = make(shape + "}");
  auto learned = make(shape + ", base: bones, blend: learned}");
  // The same weights; the decoder's 4th output (the gate's logit) set to a
  // constant L by a zero weight row.
  {
    at::NoGradGuard no_grad;
    auto to = learned->named_parameters();
    for (const auto& from : inertial->named_parameters())
      to[from.key()].narrow(0, 0, from.value().size(0)).copy_(from.value());
    to["decoder.out.weight"][3].zero_();
  }
  auto with_logit = [&](double logit) {
    {
      at::NoGradGuard no_grad;
      learned->named_parameters()["decoder.out.bias"][3].fill_(logit);
    }
    return learned->step(in);
  };
  for (auto& m : {inertial, learned}) {
    m->set_normalization(ln::testing::scene_normalization(scene));
    m->prepare(scene.statics);
  }
  const zoo::StepOutput paper = inertial->step(in);
  const zoo::StepOutput closed = with_logit(-40), open = with_logit(40), half = with_logit(0);
  for (std::size_t k = 0; k < paper.garments.size(); ++k) {
    const at::Tensor x = in.garments[k].current;
    // Gate 0: the paper's inertial step; gate 1: the bones' motion for
    // every vertex, near the body or not; gate 1/2: halfway.
    EXPECT_TRUE(at::allclose(closed.garments[k], paper.garments[k], 1e-5, 1e-6)) << k;
    const at::Tensor bones_minus_inertia = spine_turn(in, x) - root_velocity(in, k);
    EXPECT_TRUE(at::allclose(open.garments[k] - closed.garments[k], bones_minus_inertia, 1e-5, 1e-6)) << k;
    EXPECT_TRUE(at::allclose(half.garments[k], (open.garments[k] + closed.garments[k]) / 2, 1e-5, 1e-6)) << k;
    EXPECT_GT((open.garments[k] - closed.garments[k]).abs().max().item<double>(), 1e-4) << k;
  }
  // Nothing to blend with the inertial base.
  EXPECT_THROW(make("{blend: learned}"), layers::InputError);
  EXPECT_THROW(make("{base: body, blend: sometimes}"), layers::InputError);
}

TEST(LayersNet, AnyNumberOfGarments) {
  at::manual_seed(2);
  auto model = make("{width: 32, blocks: 1, heads: 2}");
  for (int garments : {1, 3}) {
    ln::testing::SceneSize size;
    size.garments = garments;
    size.garment_rows = 7 + garments;  // unseen shapes: nothing garment-specific in the weights
    const auto scene = ln::testing::make_scene(size, "g" + std::to_string(garments));
    model->prepare(scene.statics);
    const zoo::StepOutput out = model->step(scene.input(2));
    ASSERT_EQ(out.garments.size(), static_cast<std::size_t>(garments));
    for (int k = 0; k < garments; ++k) {
      EXPECT_EQ(out.garments[k].size(0), size.garment_rows * size.garment_cols);
      EXPECT_TRUE(at::isfinite(out.garments[k]).all().item<bool>());
    }
  }
}

TEST(LayersNet, SharedAttributesMakeOneTokenAndMissingOnesNone) {
  auto scene = ln::testing::make_scene({}, "shared");
  scene.statics.garments[1].attributes = scene.statics.garments[0].attributes.clone();
  auto model = make("{width: 16, blocks: 1, heads: 2}");
  model->prepare(scene.statics);
  model->step(scene.input(1));
  EXPECT_EQ(model->last_counts().abstract_tokens, 2);  // gravity + one attribute token

  scene.statics.id = "none";
  for (auto& g : scene.statics.garments) g.attributes = at::zeros({0});
  model->prepare(scene.statics);
  model->step(scene.input(1));
  EXPECT_EQ(model->last_counts().abstract_tokens, 1);  // gravity only
}

TEST(LayersNet, RejectsBadParametersAndStaticData) {
  EXPECT_THROW(make("{heads: 3}"), layers::InputError);
  EXPECT_THROW(make("{width: 100}"), layers::InputError);  // 8 heads do not divide 100
  EXPECT_THROW(make("{patch_size: 0}"), layers::InputError);
  EXPECT_THROW(make("{patch_sise: 0.1}"), layers::InputError);
  EXPECT_EQ(cfg::to_yaml(make("{blocks: 2}")->config()).find("blocks: 2") != std::string::npos, true);

  auto scene = ln::testing::make_scene({}, "bad");
  scene.statics.garments[1].attributes = at::ones({5});
  auto model = make("{width: 16, blocks: 1, heads: 2}");
  try {
    model->prepare(scene.statics);
    FAIL() << "no error";
  } catch (const layers::InputError& e) {
    EXPECT_EQ(e.file(), "sequence 'bad' garments[1] (garment1)");
    EXPECT_EQ(e.field(), "attributes");
  }
}

TEST(LayersNet, PluginRegistersTheModel) {
  zoo::Registry registry;
  zoo::load_file(registry, LAYERSNET_PLUGIN_FILE);
  ASSERT_TRUE(registry.contains("layersnet"));
  auto model = registry.create("layersnet", cfg::parse("{width: 32, heads: 4}", "p.yaml"));
  EXPECT_GT(model->info().parameters, 10000);
}

TEST(LayersNet, OverfitsOneWindow) {
  at::manual_seed(3);
  const auto scene = ln::testing::make_scene({});
  auto model = make("{width: 32, blocks: 1, heads: 4}");
  model->set_normalization(ln::testing::scene_normalization(scene));
  model->prepare(scene.statics);
  const zoo::StepInput input = scene.input(4);
  const std::vector<at::Tensor> target = scene.target(4);

  torch::optim::Adam adam(model->parameters(), torch::optim::AdamOptions(1e-3));
  auto loss_of = [&](const zoo::StepOutput& out) {
    at::Tensor loss = at::zeros({});
    std::int64_t n = 0;
    for (std::size_t k = 0; k < target.size(); ++k) {
      loss = loss + (out.garments[k] - target[k]).pow(2).sum();
      n += target[k].size(0);
    }
    return loss / static_cast<double>(n);
  };
  const double before = position_mse(model->step(input).garments, target);
  for (int i = 0; i < 200; ++i) {
    adam.zero_grad();
    at::Tensor loss = loss_of(model->step(input));
    loss.backward();
    adam.step();
  }
  const double after = position_mse(model->step(input).garments, target);
  EXPECT_LT(after, before / 10) << "before " << before << " after " << after;
  std::cout << "position MSE before " << before << " after " << after << " (m^2)\n";
}
