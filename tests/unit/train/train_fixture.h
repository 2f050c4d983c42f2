// tests/unit/train/train_fixture.h -- a small synthetic dataset folder
// (with splits and stats.h5) and a tiny trainable model registered in a
// local registry, shared by the libs/train tests.
#pragma once

#include <ATen/ATen.h>

#include <memory>
#include <string>

#include "layers/core/config.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/stats.h"
#include "layers/train/experiment_config.h"
#include "layers/zoo/model.h"
#include "layers/zoo/registry.h"
#include "synthetic_sequence.h"

namespace layers::train::testing {

// Predicts p(t+1) = p(t) + gain * (p(t) - p(t-1)) + shift: learns the
// synthetic sequences' motion (constant velocity plus drift).
struct TinyParams {
  double gain = 0.0;
  template <class V>
  void visit(V& v) {
    v("gain", gain);
  }
};

class TinyModel : public zoo::Model {
 public:
  explicit TinyModel(double gain) : Model("tiny") {
    gain_ = register_parameter("gain", at::scalar_tensor(gain, at::kFloat));
    shift_ = register_parameter("shift", at::zeros({3}, at::kFloat));
  }
  cfg::Node config() const override {
    TinyParams p;
    p.gain = gain_.item<double>();
    return cfg::to_node(p);
  }
  at::Tensor gain_, shift_;

 protected:
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    zoo::StepOutput out;
    for (const zoo::GarmentState& g : in.garments)
      out.garments.push_back(g.current + gain_ * (g.current - g.prev) + shift_ * 0.01);
    return out;
  }
};

// Multiplies positions every step: diverges within a few frames.
class ExplodingModel : public zoo::Model {
 public:
  ExplodingModel() : Model("exploding") {}
  cfg::Node config() const override { return cfg::Node(); }

 protected:
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    zoo::StepOutput out;
    for (const zoo::GarmentState& g : in.garments) out.garments.push_back(g.current * 3.0);
    return out;
  }
};

// Planted crossings: puts each garment's rest shape (a cylinder around
// the synthetic body's axis, 5 cm outside it) on the root of the predicted
// frame, then moves it along x by `all_dx`, outer garments by `outer_dx`
// more. all_dx = 0.2 pushes garment faces through the body (radius 0.15);
// outer_dx = 0.05 pushes the outer cylinder (radius 0.23) through the inner
// one (0.2) and keeps both clear of the body. The ground truth crosses
// nothing (write_dataset's garments are concentric, below the body).
class PlantedModel : public zoo::Model {
 public:
  PlantedModel(const std::string& name, double all_dx, double outer_dx)
      : Model(name), all_dx_(all_dx), outer_dx_(outer_dx) {}
  cfg::Node config() const override { return cfg::Node(); }

 protected:
  zoo::StepOutput predict(const zoo::StepInput& in) override {
    zoo::StepOutput out;
    const at::Tensor root_next = in.root[2];
    for (const zoo::GarmentStatic& g : sequence().garments) {
      const double dx = all_dx_ + (g.layer != 0 ? outer_dx_ : 0.0);
      const at::Tensor shift = at::tensor({static_cast<float>(dx), 0.0f, 0.0f}, at::kFloat);
      out.garments.push_back(g.rest + root_next + shift);
    }
    return out;
  }

 private:
  double all_dx_, outer_dx_;
};

inline void register_test_models(zoo::Registry& registry) {
  registry.add("tiny", "test model", [](const cfg::Node& params) -> std::shared_ptr<zoo::Model> {
    return std::make_shared<TinyModel>(cfg::read<TinyParams>(params).gain);
  });
  registry.add("exploding", "test model",
               [](const cfg::Node&) -> std::shared_ptr<zoo::Model> { return std::make_shared<ExplodingModel>(); });
  registry.add("through_body", "test model", [](const cfg::Node&) -> std::shared_ptr<zoo::Model> {
    return std::make_shared<PlantedModel>("through_body", 0.2, 0.0);
  });
  registry.add("through_inner", "test model", [](const cfg::Node&) -> std::shared_ptr<zoo::Model> {
    return std::make_shared<PlantedModel>("through_inner", 0.0, 0.05);
  });
}

// A dataset folder with `n` sequences of `frames` frames: the first n-2 in
// train, then one val and one test.
inline std::string write_dataset(const std::string& folder, int n = 5, std::int64_t frames = 12) {
  data::DatasetWriterOptions options;
  options.name = "synthetic";
  options.sequences_per_shard = 2;
  data::DatasetWriter writer(folder, options);
  std::vector<std::string> ids;
  data::testing::SyntheticSize size;
  size.frames = frames;
  for (int i = 0; i < n; ++i) {
    data::SequenceData seq = data::testing::make_sequence("s" + std::to_string(i), 100 + i, size);
    for (data::GarmentData& g : seq.garments) {
      // Smooth motion a model can learn: constant velocity (differing per
      // sequence) instead of the fixture's random root jitter.
      const float vx = 0.005f * static_cast<float>(i + 1), vz = 0.003f;
      for (std::int64_t t = 0; t < frames; ++t)
        for (std::size_t v = 0; v < g.rest.size(); v += 3) {
          float* p = g.positions.data() + t * static_cast<std::int64_t>(g.rest.size()) + v;
          p[0] = g.rest[v] + vx * static_cast<float>(t);
          p[1] = g.rest[v + 1];
          p[2] = g.rest[v + 2] + vz * static_cast<float>(t);
        }
      g.attributes = {{"mass", 0.3},   {"tension", 20},  {"compression", 30},  {"shear", 40},
                      {"bending", 50}, {"friction", 60}, {"self_friction", 70}};
    }
    writer.add(seq);
    ids.push_back(seq.id);
  }
  writer.set_split("train", std::vector<std::string>(ids.begin(), ids.end() - 2));
  writer.set_split("val", {ids[ids.size() - 2]});
  writer.set_split("test", {ids.back()});
  writer.set_split("T", {ids[0], ids.back()});
  writer.finish();
  data::write_dataset_stats(folder, data::compute_stats(data::Dataset::open(folder)));
  return folder;
}

inline ExperimentConfig experiment(const std::string& dataset, const std::string& output, const std::string& model) {
  cfg::Node tree = cfg::parse("run: {seed: 3, threads: 1, output: '" + output +
                                  "'}\n"
                                  "data: {dataset: '" +
                                  dataset +
                                  "'}\n"
                                  "model: {name: " +
                                  model +
                                  "}\n"
                                  "loss: {normal: 0, body_collision: 0}\n"
                                  "train: {epochs: 2, batch_size: 2, val_horizon: 4, lr: 0.01}\n"
                                  "eval: {horizon: 6}\n",
                              "test.yaml");
  return read_experiment(tree, "test.yaml");
}

}  // namespace layers::train::testing
