// The Model interface: a model created from a plugin runs a step; static
// data validation, conversion and caching; step input/output checks. The
// only torch translation unit of test_zoo.
#include <gtest/gtest.h>

#include "error_of.h"
#include "layers/core/config_node.h"
#include "layers/core/error.h"
#include "layers/zoo/model.h"
#include "layers/zoo/plugin_loader.h"
#include "test_paths.h"

namespace zoo = layers::zoo;
namespace cfg = layers::cfg;

namespace {

// One garment made of one triangle (int32 indices, as stored in LAYERS-H5).
zoo::SequenceStatic triangle_sequence(const std::string& id) {
  zoo::SequenceStatic s;
  s.id = id;
  s.body_faces = at::tensor({0, 1, 2, 1, 3, 2}, at::kInt).reshape({2, 3});
  zoo::GarmentStatic g;
  g.name = "shirt";
  g.type = "tshirt";
  g.layer = 0;
  g.faces = at::tensor({0, 1, 2}, at::kInt).reshape({1, 3});
  g.rest = at::tensor({0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}).reshape({3, 3});
  g.uv = at::tensor({0.f, 0.f, 1.f, 0.f, 0.f, 1.f}).reshape({3, 2});
  g.uv_faces = g.faces.clone();
  g.panel = at::zeros({1}, at::kInt);
  g.attributes = at::full({7}, 0.5f);
  s.garments.push_back(g);
  return s;
}

zoo::StepInput triangle_input(const at::Tensor& prev, const at::Tensor& current) {
  zoo::StepInput in;
  in.garments.push_back({prev, current});
  in.body = at::zeros({4, 3});
  in.body_next = at::zeros({4, 3});
  in.root = at::zeros({3, 3});
  in.root_rot = at::zeros({3, 4});
  in.wind_rotation = at::zeros({2, 4});
  in.wind_strength = at::zeros({2});
  return in;
}

std::shared_ptr<zoo::Model> plugin_model(zoo::Registry& r, const std::string& yaml) {
  zoo::load_file(r, layers::test::plugin_file("test_constant_velocity"));
  return r.create("test_constant_velocity", cfg::parse(yaml, "exp.yaml"));
}

// A model that counts derive() calls and derives the garments' edge
// counts (3 per triangle, as a stand-in for real derived data).
class CountingModel : public zoo::Model {
 public:
  CountingModel() : Model("counting") {}
  int derives = 0;
  cfg::Node config() const override { return cfg::Node{}; }
  std::int64_t face_count() const { return derived<Faces>().count; }

 protected:
  struct Faces : Derived {
    std::int64_t count = 0;
  };
  std::shared_ptr<const Derived> derive(const zoo::SequenceStatic& s) override {
    ++derives;
    auto d = std::make_shared<Faces>();
    for (const auto& g : s.garments) d->count += g.faces.size(0);
    return d;
  }
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    return {{in.garments[0].current, in.garments[0].current}};  // one too many
  }
};

}  // namespace

TEST(Model, PluginModelRunsOneStep) {
  zoo::Registry r;
  auto model = plugin_model(r, "damping: 0.25\n");
  zoo::ModelInfo info = model->info();
  EXPECT_EQ(info.name, "test_constant_velocity");
  EXPECT_EQ(info.parameters, 1);
  EXPECT_EQ(info.trainable, 1);
  EXPECT_EQ(cfg::to_yaml(model->config()), "damping: 0.25\n");

  model->prepare(triangle_sequence("seq-a"));
  at::Tensor prev = at::tensor({0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}).reshape({3, 3});
  at::Tensor current = prev + at::tensor({0.f, 0.04f, 0.f});  // moving up 4 cm per frame
  zoo::StepOutput out = model->step(triangle_input(prev, current));
  ASSERT_EQ(out.garments.size(), 1u);
  // p(t+1) = p(t) + (1 - 0.25) * 4 cm up.
  at::Tensor expected = current + at::tensor({0.f, 0.03f, 0.f});
  EXPECT_TRUE(at::allclose(out.garments[0], expected, 1e-6, 1e-7)) << out.garments[0];

  // The damping is a real, trainable parameter: the step has a gradient.
  out.garments[0].sum().backward();
  at::Tensor grad = model->parameters()[0].grad();
  ASSERT_TRUE(grad.defined());
  EXPECT_NEAR(grad.item<float>(), -0.04f * 3, 1e-6);
}

TEST(Model, PluginModelRejectsBadParameters) {
  zoo::Registry r;
  std::string unknown = layers::test::error_of([&] { plugin_model(r, "dampng: 0.1\n"); });
  EXPECT_NE(unknown.find("dampng"), std::string::npos) << unknown;
  EXPECT_NE(unknown.find("exp.yaml"), std::string::npos) << unknown;
  zoo::Registry r2;
  EXPECT_THROW(plugin_model(r2, "damping: -1\n"), layers::InputError);  // the type survives the plugin
  std::string range = layers::test::error_of([&] { plugin_model(r2, "damping: 2\n"); });
  EXPECT_NE(range.find("exp.yaml:1: damping: expected a number in [0, 1], got '2'"), std::string::npos) << range;
}

TEST(Model, PrepareConvertsAndValidatesStaticData) {
  CountingModel m;
  EXPECT_EQ(layers::test::error_of([&] { m.sequence(); }), "model 'counting': step or sequence() before prepare()");
  m.prepare(triangle_sequence("s"));
  EXPECT_EQ(m.sequence().garments[0].faces.scalar_type(), at::kLong);
  EXPECT_EQ(m.sequence().body_faces.scalar_type(), at::kLong);
  EXPECT_EQ(m.sequence().garments[0].rest.scalar_type(), at::kFloat);

  zoo::SequenceStatic bad = triangle_sequence("bad");
  bad.garments[0].faces[0][2] = 5;
  EXPECT_EQ(layers::test::error_of([&] { m.prepare(bad); }),
            "sequence 'bad': garments[0] (shirt).faces: expected indices in [0, 3), got values in [0, 5]");
  bad = triangle_sequence("bad");
  bad.garments[0].rest = at::zeros({3, 2});
  EXPECT_EQ(layers::test::error_of([&] { m.prepare(bad); }),
            "sequence 'bad': garments[0] (shirt).rest: expected a floating-point tensor [*, 3], got Float "
            "tensor [3, 2] on cpu");
  bad = triangle_sequence("bad");
  bad.garments[0].attributes[3] = std::nanf("");
  EXPECT_EQ(layers::test::error_of([&] { m.prepare(bad); }),
            "sequence 'bad': garments[0] (shirt).attributes: expected finite values, got NaN or infinity");
  bad = triangle_sequence("bad");
  bad.garments[0].layer = 2;
  EXPECT_THROW(m.prepare(bad), layers::InputError);
}

TEST(Model, DerivedDataIsCachedPerSequence) {
  CountingModel m;
  m.set_cache_capacity(2);
  zoo::SequenceStatic two = triangle_sequence("two");
  two.garments.push_back(two.garments[0]);
  m.prepare(triangle_sequence("one"));
  EXPECT_EQ(m.face_count(), 1);
  m.prepare(two);
  EXPECT_EQ(m.face_count(), 2);
  m.prepare(triangle_sequence("one"));  // cached
  EXPECT_EQ(m.derives, 2);
  EXPECT_EQ(m.face_count(), 1);
  m.prepare(triangle_sequence("three"));  // evicts "two", the least recently used
  EXPECT_EQ(m.cached_sequences(), 2u);
  m.prepare(two);
  EXPECT_EQ(m.derives, 4);
  EXPECT_EQ(m.face_count(), 2);
}

TEST(Model, StepChecksInputAndOutput) {
  CountingModel m;
  m.prepare(triangle_sequence("s"));
  at::Tensor p = at::zeros({3, 3});
  zoo::StepInput in = triangle_input(p, at::zeros({4, 3}));
  EXPECT_EQ(layers::test::error_of([&] { m.step(in); }),
            "model 'counting': step input garments[0].current: expected a floating-point tensor [3, 3] on "
            "cpu, got Float tensor [4, 3] on cpu");
  in = triangle_input(p, p);
  in.wind_strength = at::Tensor();
  EXPECT_EQ(layers::test::error_of([&] { m.step(in); }),
            "model 'counting': step input wind_strength: expected a floating-point tensor [2] on cpu, got "
            "nothing (undefined tensor)");
  in = triangle_input(p, p);
  in.garments.clear();
  EXPECT_EQ(layers::test::error_of([&] { m.step(in); }),
            "model 'counting': step input garments: expected 1 garments (as prepared), got 0");
  EXPECT_EQ(layers::test::error_of([&] { m.step(triangle_input(p, p)); }),
            "model 'counting': step output garments: expected 1 garments (as prepared), got 2");
}
