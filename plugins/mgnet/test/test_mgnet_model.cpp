// The MGNet model through the zoo interface: forward on a two-garment
// sequence, on garments with UV charts it has never seen, parameters and
// their errors, bad static data, diverged input, and the plugin itself.
#include <gtest/gtest.h>

#include <limits>

#include "error_of.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/zoo/model.h"
#include "layers/zoo/plugin_loader.h"
#include "layers/zoo/registry.h"
#include "mgnet_fixture.h"
#include "spec.h"

namespace zoo = layers::zoo;
namespace cfg = layers::cfg;
using namespace layers::mgnet::testing;

namespace {

const char* kSmall = "{resolution: 16, channels: [8, 16], latent: 16}";

std::shared_ptr<zoo::Model> small_model() {
  at::manual_seed(0);
  return layers::mgnet::make_mgnet(cfg::parse(kSmall, "test.yaml"));
}

// The default base, body_seeds: each vertex moves with its nearest body
// vertex; the fixture's body moves rigidly with the root, so every seed
// point moves by root(t+1) - root(t).
at::Tensor base_prediction(const zoo::StepInput& in, std::size_t k) {
  return in.garments[k].current + in.root[2] - in.root[1];
}

// The constant_velocity base (root-relative).
at::Tensor velocity_base_prediction(const zoo::StepInput& in, std::size_t k) {
  const at::Tensor rel = in.garments[k].current - in.root[1], prev = in.garments[k].prev - in.root[0];
  return 2 * rel - prev + in.root[2];
}

void expect_prediction(const zoo::StepOutput& out, const zoo::StepInput& in,
                       at::Tensor (*base)(const zoo::StepInput&, std::size_t) = base_prediction) {
  ASSERT_EQ(out.garments.size(), in.garments.size());
  for (std::size_t k = 0; k < out.garments.size(); ++k) {
    EXPECT_EQ(out.garments[k].sizes(), in.garments[k].current.sizes());
    EXPECT_TRUE(at::isfinite(out.garments[k]).all().item<bool>());
    // A fresh model stays near its base prediction but does move off it.
    const double off = (out.garments[k] - base(in, k)).abs().max().item<double>();
    EXPECT_LT(off, 0.01);
    EXPECT_GT(off, 0.0);
  }
}

// A garment on another template: 6 x 20 vertices, its UVs two mirrored
// panels side by side (u in [0, 2] metres), narrower than the first ones.
zoo::GarmentStatic unseen_garment() {
  const std::int64_t rows = 6, cols = 20;
  zoo::GarmentStatic g = grid_garment("cape", 1, grid_cylinder(rows, cols, 0.2f, 0.5f), rows, cols);
  const at::Tensor uv = grid_uv(rows, cols, 0.f, 0.f, 2.f, 0.7f);
  const at::Tensor u = uv.select(1, 0);
  g.uv = at::stack({at::where(u < 1, 1 - u, u + 0.1), uv.select(1, 1)}, 1);
  return g;
}

std::string error_of_params(const std::string& yaml) {
  return layers::test::error_of<layers::InputError>([&] { layers::mgnet::make_mgnet(cfg::parse(yaml, "bad.yaml")); });
}

}  // namespace

TEST(MGNet, ForwardOnTwoGarmentsGivesFiniteOutputsOfTheRightShapes) {
  auto model = small_model();
  const Scene scene = two_garment_scene("two");
  model->prepare(scene.statics);
  const zoo::StepInput in = scene.input(2);
  expect_prediction(model->step(in), in);
  // Shared weights see a batch of two images; the output depends on the
  // layer map, not only on the geometry: swapping the layers changes it.
  Scene swapped = scene;
  swapped.statics.id = "two-swapped";
  swapped.statics.garments[0].layer = 1;
  swapped.statics.garments[1].layer = 0;
  const zoo::StepOutput a = model->step(in);
  model->prepare(swapped.statics);
  const zoo::StepOutput b = model->step(in);
  EXPECT_FALSE(at::allclose(a.garments[0], b.garments[0], 0, 1e-9));
}

TEST(MGNet, RunsOnGarmentsWithUnseenUvCharts) {
  auto model = small_model();
  const Scene scene = two_garment_scene("seen");
  model->prepare(scene.statics);
  model->step(scene.input(1));

  // Another template (other vertex count and UV layout), alone and with
  // the first sequence's inner garment.
  Scene other = two_garment_scene("unseen");
  other.statics.garments[1] = unseen_garment();
  model->prepare(other.statics);
  const zoo::StepInput in = other.input(3);
  expect_prediction(model->step(in), in);

  Scene alone = other;
  alone.statics.id = "unseen-alone";
  alone.statics.garments.erase(alone.statics.garments.begin());
  model->prepare(alone.statics);
  const zoo::StepInput one = alone.input(3);
  expect_prediction(model->step(one), one);
  EXPECT_EQ(model->cached_sequences(), 3u);
}

TEST(MGNet, ConstantVelocityBaseKeepsTheRelativeVelocity) {
  at::manual_seed(0);
  auto model = layers::mgnet::make_mgnet(
      cfg::parse("{resolution: 16, channels: [8, 16], latent: 16, base: constant_velocity}", "test.yaml"));
  EXPECT_EQ(model->config().find("base")->scalar, "constant_velocity");
  const Scene scene = two_garment_scene("velocity");
  model->prepare(scene.statics);
  const zoo::StepInput in = scene.input(2);
  expect_prediction(model->step(in), in, velocity_base_prediction);
}

TEST(MGNet, NormalizationScalesTheInputsAndTheDisplacement) {
  auto model = small_model();
  const Scene scene = two_garment_scene("norm");
  model->prepare(scene.statics);
  const zoo::StepInput in = scene.input(2);
  const at::Tensor before = model->step(in).garments[0] - base_prediction(in, 0);
  layers::data::NormStats stats;
  stats.garment_acceleration.std = {0.01, 0.01, 0.01};
  stats.garment_velocity.std = {0.02, 0.02, 0.02};
  stats.garment_position.mean = {0.0, -0.2, 0.0};
  stats.garment_position.std = {0.3, 0.4, 0.3};
  model->set_normalization(zoo::Normalization::from_stats(stats));
  const at::Tensor after = model->step(in).garments[0] - base_prediction(in, 0);
  EXPECT_TRUE(at::isfinite(after).all().item<bool>());
  EXPECT_FALSE(at::allclose(before * 0.01, after, 0, 1e-9));  // the inputs changed too
  EXPECT_LT(after.abs().max().item<double>(), before.abs().max().item<double>());
}

TEST(MGNet, DefaultsAndConfigRoundTrip) {
  auto model = layers::mgnet::make_mgnet(cfg::Node{});
  const cfg::Node config = model->config();
  EXPECT_EQ(config.find("resolution")->scalar, "64");
  ASSERT_EQ(config.find("channels")->seq.size(), 3u);
  EXPECT_EQ(config.find("channels")->seq[2].scalar, "128");
  EXPECT_EQ(config.find("latent")->scalar, "64");
  EXPECT_EQ(config.find("base")->scalar, "body_seeds");
  EXPECT_EQ(cfg::to_yaml(layers::mgnet::make_mgnet(config)->config()), cfg::to_yaml(config));
  EXPECT_GT(model->info().parameters, 100000);
  EXPECT_EQ(model->name(), "mgnet");
}

TEST(MGNet, BadParametersAreInputErrors) {
  std::string m = error_of_params("{resolution: 30, channels: [8, 16]}");
  EXPECT_NE(m.find("bad.yaml:1"), std::string::npos) << m;
  EXPECT_NE(m.find("resolution"), std::string::npos) << m;
  EXPECT_NE(m.find("multiple of 2^2"), std::string::npos) << m;
  m = error_of_params("{channels: []}");
  EXPECT_NE(m.find("channels"), std::string::npos) << m;
  EXPECT_NE(m.find("at least one"), std::string::npos) << m;
  m = error_of_params("{latent: 0}");
  EXPECT_NE(m.find("latent"), std::string::npos) << m;
  m = error_of_params("{base: skinned}");
  EXPECT_NE(m.find("base"), std::string::npos) << m;
  EXPECT_NE(m.find("body_seeds"), std::string::npos) << m;
  m = error_of_params("{width: 128}");
  EXPECT_NE(m.find("width"), std::string::npos) << m;
}

TEST(MGNet, GarmentWithoutUvExtentIsAnInputErrorAtPrepare) {
  auto model = small_model();
  Scene scene = two_garment_scene("flat-uv");
  scene.statics.garments[1].uv.select(1, 0).fill_(0.5f);
  const std::string m = layers::test::error_of<layers::InputError>([&] { model->prepare(scene.statics); });
  EXPECT_NE(m.find("sequence 'flat-uv' garments[1] (outer)"), std::string::npos) << m;
  EXPECT_NE(m.find("uv"), std::string::npos) << m;
}

TEST(MGNet, DivergedInputGivesNonFiniteOutputWithoutFailing) {
  auto model = small_model();
  const Scene scene = two_garment_scene("diverged");
  model->prepare(scene.statics);
  zoo::StepInput in = scene.input(2);
  in.garments[0].current = in.garments[0].current.clone();
  in.garments[0].current[3].fill_(std::numeric_limits<float>::quiet_NaN());
  const zoo::StepOutput out = model->step(in);
  ASSERT_EQ(out.garments.size(), 2u);
  EXPECT_FALSE(at::isfinite(out.garments[0]).all().item<bool>());
}

TEST(MGNet, PluginRegistersTheModel) {
  zoo::Registry registry;
  const zoo::LoadedPlugin plugin = zoo::load_file(registry, LAYERS_MGNET_PLUGIN);
  ASSERT_EQ(plugin.models, std::vector<std::string>{"mgnet"});
  auto model = registry.create("mgnet", cfg::parse(kSmall, "test.yaml"));
  const Scene scene = two_garment_scene("plugin");
  model->prepare(scene.statics);
  const zoo::StepInput in = scene.input(1);
  expect_prediction(model->step(in), in);
}
