// The DeePSD model on a synthetic skinned scene (deepsd_fixture.h):
// skinning against hand-computed LBS, forced heads reproducing plain
// skinning, shapes and finiteness for two garments, the first-epoch priors,
// the heads reused without gradients, errors, and the built plugin with the configs
// in configs/models.
#include <gtest/gtest.h>

#include <ATen/core/grad_mode.h>

#include <limits>

#include "deepsd_fixture.h"
#include "deepsd_model.h"
#include "error_of.h"
#include "layers/core/config_node.h"
#include "layers/core/error.h"
#include "layers/zoo/model_config.h"
#include "layers/zoo/plugin_loader.h"
#include "layers/zoo/registry.h"
#include "layers/zoo/skinning.h"
#include "test_paths.h"

namespace layers::deepsd {
namespace {

using namespace testing;

// Small sizes: the tests are about wiring, not capacity.
DeepsdParams small_params() { return scene_params(8); }

double max_error(const at::Tensor& got, const std::vector<Eigen::Vector3d>& want) {
  const at::Tensor g = got.to(at::kDouble).contiguous();
  double worst = 0;
  for (std::size_t v = 0; v < want.size(); ++v)
    for (int c = 0; c < 3; ++c)
      worst = std::max(worst, std::abs(g[static_cast<std::int64_t>(v)][c].item<double>() - want[v][c]));
  return worst;
}

// Forces the blend weights of every vertex to joint `joint` (softmax of
// logits 0 and -1000 is exactly one-hot in float) and the deformation to 0.
void force_plain_skinning(DeepsdModel& model, int joint) {
  at::NoGradGuard no_grad;
  auto& w = model.weight_head().last();
  w->weight.zero_();
  w->bias.fill_(-1000.0f);
  w->bias[joint].fill_(0.0f);
  model.deformation_head().last()->weight.zero_();
  model.deformation_head().last()->bias.zero_();
}

using layers::zoo::dense_weights;
using layers::zoo::skin;
using layers::zoo::tpose_to_frame;
using layers::zoo::unskin;

TEST(DeepsdSkinning, OneHotAndBlendedWeightsMatchHandComputedLbs) {
  const Scene scene;
  const Skeleton frame = posed(0.9);
  const at::Tensor maps = tpose_to_frame(to_tensor(scene.t), to_tensor(frame));
  const std::vector<Eigen::Vector3d>& x = scene.body.vertices;
  const auto n = static_cast<std::int64_t>(x.size());

  // One-hot, a different joint per vertex.
  at::Tensor one_hot = at::zeros({n, kJoints});
  std::vector<Eigen::Vector3d> want;
  for (std::int64_t v = 0; v < n; ++v) {
    one_hot[v][v % kJoints] = 1.0f;
    want.push_back(move(frame[v % kJoints], scene.t[v % kJoints], x[v]));
  }
  EXPECT_LT(max_error(skin(points_tensor(x), one_hot, maps), want), 2e-6);

  // Blended weights; and the body mapped back to the T-pose exactly.
  const at::Tensor s = scene.statics().skin_weight;
  want.clear();
  for (std::int64_t v = 0; v < n; ++v) want.push_back(lbs(frame, scene.t, scene.body_weights[v], x[v]));
  const at::Tensor weights = dense_weights(scene.statics().skin_index, s, kJoints);
  const at::Tensor posed_body = skin(points_tensor(x), weights, maps);
  EXPECT_LT(max_error(posed_body, want), 2e-6);
  EXPECT_LT(max_error(unskin(posed_body, scene.statics().skin_index, s, maps), x), 2e-6);
}

TEST(DeepsdModel, ForcedHeadsReproducePlainSkinningExactly) {
  const Scene scene;
  const Skeleton frame = posed(0.8);
  DeepsdModel model(small_params());
  model.prepare(scene.statics());
  for (int joint = 0; joint < kJoints; ++joint) {
    force_plain_skinning(model, joint);
    const zoo::StepOutput out = model.step(scene.input(frame));
    ASSERT_EQ(out.garments.size(), 2u);
    for (std::size_t k = 0; k < 2; ++k) {
      std::vector<Eigen::Vector3d> want;
      for (const auto& x : scene.garments[k].vertices) want.push_back(move(frame[joint], scene.t[joint], x));
      EXPECT_LT(max_error(out.garments[k], want), 2e-6) << "joint " << joint << " garment " << k;
    }
  }
}

TEST(DeepsdModel, AtTheTposeWithoutDeformationTheRestShapeComesBack) {
  const Scene scene;
  DeepsdModel model(small_params());  // random weights; deformation head starts at zero
  model.prepare(scene.statics());
  const zoo::StepOutput out = model.step(scene.input(scene.t));
  for (std::size_t k = 0; k < 2; ++k) EXPECT_LT(max_error(out.garments[k], scene.garments[k].vertices), 2e-6);
}

TEST(DeepsdModel, FiniteOutputsWithTheRightShapesForTwoGarments) {
  const Scene scene;
  DeepsdParams p;
  p.joints = kJoints;  // default widths otherwise
  DeepsdModel model(p);
  model.prepare(scene.statics());
  {
    at::NoGradGuard no_grad;
    model.deformation_head().last()->weight.normal_(0.0, 0.01);
  }
  const zoo::StepInput in = scene.input(posed(1.3));
  const zoo::StepOutput out = model.step(in);
  ASSERT_EQ(out.garments.size(), 2u);
  for (std::size_t k = 0; k < 2; ++k) {
    const auto v = static_cast<std::int64_t>(scene.garments[k].vertices.size());
    EXPECT_EQ(out.garments[k].sizes(), (std::vector<std::int64_t>{v, 3}));
    EXPECT_TRUE(at::isfinite(out.garments[k]).all().item<bool>());
    const GarmentHeads h = model.heads(k);
    EXPECT_EQ(h.weights.sizes(), (std::vector<std::int64_t>{v, kJoints}));
    EXPECT_EQ(h.basis.sizes(), (std::vector<std::int64_t>{v, 128, 3}));
    EXPECT_LT((h.weights.sum(1) - 1).abs().max().item<double>(), 1e-5);
    EXPECT_GE(h.weights.min().item<double>(), 0.0);
  }
  EXPECT_EQ(model.pose_embedding(in).sizes(), (std::vector<std::int64_t>{128}));
  // The wind is an input: another strength moves the garments.
  const zoo::StepOutput calm = model.step(scene.input(posed(1.3), 0.0));
  EXPECT_GT((calm.garments[1] - out.garments[1]).abs().max().item<double>(), 1e-7);
}

TEST(DeepsdModel, WithoutWindInputTheWindChangesNothing) {
  const Scene scene;
  DeepsdParams p = small_params();
  p.wind = false;
  DeepsdModel model(p);
  model.prepare(scene.statics());
  {
    at::NoGradGuard no_grad;
    model.deformation_head().last()->weight.normal_(0.0, 0.1);
  }
  const at::Tensor a = model.step(scene.input(posed(0.4), 0.0)).garments[0];
  const at::Tensor b = model.step(scene.input(posed(0.4), 390.0)).garments[0];
  EXPECT_TRUE(at::equal(a, b));
}

TEST(DeepsdModel, FirstEpochPriorsArePresentAtEpochZeroAndAbsentAtEpochOne) {
  const Scene scene;
  DeepsdParams p = small_params();
  p.weight_prior = 3.0;
  p.deformation_prior = 0.5;
  DeepsdModel model(p);
  model.prepare(scene.statics());
  {
    at::NoGradGuard no_grad;
    model.deformation_head().last()->bias.fill_(0.01f);
  }
  model.step(scene.input(posed(0.6)));

  const std::vector<zoo::LossTerm> first = model.auxiliary_losses({0, 0});
  ASSERT_EQ(first.size(), 2u);
  EXPECT_EQ(first[0].name, "weight_prior");
  EXPECT_EQ(first[1].name, "deformation_prior");
  EXPECT_TRUE(first[0].value.requires_grad());
  EXPECT_GT(first[1].value.item<double>(), 0.0);
  EXPECT_TRUE(model.auxiliary_losses({1, 100}).empty());

  // The weight prior's targets are the weights of the body vertex nearest
  // to each rest vertex in the T-pose (found here by brute force).
  double sum = 0;
  std::int64_t count = 0;
  for (std::size_t k = 0; k < 2; ++k) {
    const at::Tensor w = model.heads(k).weights.detach().to(at::kDouble);
    const auto& rest = scene.garments[k].vertices;
    for (std::size_t v = 0; v < rest.size(); ++v) {
      std::size_t nearest = 0;
      for (std::size_t b = 1; b < scene.body.vertices.size(); ++b)
        if ((scene.body.vertices[b] - rest[v]).squaredNorm() < (scene.body.vertices[nearest] - rest[v]).squaredNorm())
          nearest = b;
      for (int j = 0; j < kJoints; ++j) {
        const double d = w[static_cast<std::int64_t>(v)][j].item<double>() - scene.body_weights[nearest][j];
        sum += d * d;
      }
      ++count;
    }
  }
  EXPECT_NEAR(first[0].value.item<double>(), 3.0 * sum / double(count), 1e-5);

  // The prior's gradient reaches the blend-weight head.
  first[0].value.backward();
  EXPECT_GT(model.weight_head().last()->bias.grad().abs().sum().item<double>(), 0.0);
}

TEST(DeepsdModel, WithoutGradientsTheHeadsAreReusedUntilAParameterChanges) {
  const Scene scene;
  DeepsdModel model(small_params());
  model.prepare(scene.statics());
  const zoo::StepInput in = scene.input(posed(0.5));
  const at::Tensor with_grad = model.step(in).garments[0].detach();
  at::Tensor cached, changed;
  {
    at::NoGradGuard no_grad;
    EXPECT_TRUE(at::allclose(model.step(in).garments[0], with_grad, 0, 1e-6));
    EXPECT_EQ(model.step_counters().at("heads_reused"), 0.0);
    cached = model.step(in).garments[0];  // from the cache
    EXPECT_EQ(model.step_counters().at("heads_reused"), 1.0);
    EXPECT_EQ(model.step_counters().at("garment_vertices"), 72.0 + 84.0);
    EXPECT_TRUE(at::allclose(cached, with_grad, 0, 1e-6));
    model.weight_head().last()->bias.add_(at::arange(kJoints, at::kFloat));  // an optimiser step, say
    changed = model.step(in).garments[0];
    EXPECT_GT((changed - cached).abs().max().item<double>(), 1e-4);
  }
  // The same as computing the heads afresh with gradients.
  EXPECT_TRUE(at::allclose(model.step(in).garments[0].detach(), changed, 0, 1e-6));
}

// With gradients, the steps before a backward pass share one computation
// of the heads (a training window's loss steps); the gradient is the one
// of computing them afresh for each step, and after the pass they are made
// again.
TEST(DeepsdModel, WithGradientsTheStepsBeforeABackwardPassShareTheHeads) {
  const Scene scene;
  DeepsdModel model(small_params());
  model.prepare(scene.statics());
  const zoo::StepInput first = scene.input(posed(0.5)), second = scene.input(posed(0.7));
  const auto gradients = [&] {
    std::vector<at::Tensor> all;
    for (at::Tensor p : model.parameters()) {
      all.push_back(p.grad().defined() ? p.grad().detach().clone().flatten() : at::zeros({p.numel()}));
      if (p.grad().defined()) p.mutable_grad().zero_();
    }
    return at::cat(all);
  };
  const at::Tensor a = model.step(first).garments[0];
  EXPECT_EQ(model.step_counters().at("heads_reused"), 0.0);
  const at::Tensor b = model.step(second).garments[0];
  EXPECT_EQ(model.step_counters().at("heads_reused"), 1.0);
  (a.square().sum() + b.square().sum()).backward();
  const at::Tensor shared = gradients();

  model.step(first).garments[0].square().sum().backward();
  EXPECT_EQ(model.step_counters().at("heads_reused"), 0.0) << "made again after the backward pass";
  model.step(second).garments[0].square().sum().backward();
  EXPECT_EQ(model.step_counters().at("heads_reused"), 0.0);
  const at::Tensor separate = gradients();
  EXPECT_GT(shared.abs().sum().item<double>(), 0.0);
  EXPECT_TRUE(at::allclose(shared, separate, 1e-4, 1e-6)) << (shared - separate).abs().max().item<double>();
}

TEST(DeepsdModel, ClearErrorsForMissingDataAndBadParameters) {
  const Scene scene;
  DeepsdModel model(small_params());
  zoo::SequenceStatic s = scene.statics("old");
  s.tpose_joints = at::Tensor();
  std::string message = test::error_of<InputError>([&] { model.prepare(s); });
  EXPECT_NE(message.find("sequence 'old'"), std::string::npos) << message;
  EXPECT_NE(message.find("tpose_joints"), std::string::npos) << message;

  DeepsdParams five = small_params();
  five.joints = 5;
  DeepsdModel wrong(five);
  message = test::error_of<InputError>([&] { wrong.prepare(scene.statics()); });
  EXPECT_NE(message.find("5 joints"), std::string::npos) << message;

  model.prepare(scene.statics());
  zoo::StepInput in = scene.input(posed(0.2));
  in.joints_next = at::Tensor();
  message = test::error_of<Error>([&] { model.step(in); });
  EXPECT_NE(message.find("joints_next"), std::string::npos) << message;
  DeepsdModel fresh(small_params());
  fresh.prepare(scene.statics());
  message = test::error_of<Error>([&] { fresh.auxiliary_losses({0, 0}); });
  EXPECT_NE(message.find("a step on the current sequence first"), std::string::npos) << message;

  auto params_error = [](const std::string& yaml) {
    return test::error_of<InputError>([&] { make_deepsd_model(cfg::parse(yaml, "exp.yaml")); });
  };
  EXPECT_NE(params_error("graph_widths: []\n").find("graph_widths"), std::string::npos);
  EXPECT_NE(params_error("basis: 0\n").find("basis"), std::string::npos);
  EXPECT_NE(params_error("widht: 3\n").find("widht"), std::string::npos);
}

TEST(DeepsdPlugin, ConfigsCreateTheModelThroughThePlugin) {
  zoo::Registry registry;
  zoo::load_file(registry, LAYERS_DEEPSD_PLUGIN);
  ASSERT_TRUE(registry.contains("deepsd"));
  const cfg::Node plain = cfg::load_file(test::source_dir() + "/configs/models/deepsd.yaml");
  const cfg::Node plus = cfg::load_file(test::source_dir() + "/configs/models/deepsd_plus.yaml");
  auto model = zoo::create_model(registry, *plain.find("model"));
  EXPECT_EQ(model->name(), "deepsd");
  EXPECT_GT(model->info().trainable, 500000);
  EXPECT_EQ(cfg::to_yaml(model->config()), cfg::to_yaml(zoo::create_model(registry, *plus.find("model"))->config()));
  // deepsd+ (the paper's "with collision loss": Eq. 14 extended between
  // layers, Table 4's caption) differs only by the body and layer terms.
  EXPECT_EQ(plain.find("loss")->find("body_collision")->scalar, "0");
  EXPECT_EQ(plus.find("loss")->find("body_collision")->scalar, "1");
  EXPECT_EQ(plain.find("loss")->find("layer_collision")->scalar, "0");
  EXPECT_EQ(plus.find("loss")->find("layer_collision")->scalar, "1");
}

}  // namespace
}  // namespace layers::deepsd
