// LayersNet inference (and one training step) in ms per frame at batch 1
// on synthetic two-layer scenes of 2k, 8k and 32k garment vertices around a
// 13,340-vertex body, with the patch, body-token and edge counts each step
// used; a "far body" variant adds as many body vertices again far from the
// garment (the counts and the output do not change, only the box test).
// LAYERS_BENCH_DEVICE=cuda runs model and inputs on the GPU (CUDA builds of
// LibTorch; scripts/gpu-check.sh), each step then waits for the device.
#include <benchmark/benchmark.h>

#include <ATen/core/grad_mode.h>
#include <torch/optim/adam.h>
#include <cmath>
#include <cstdlib>
#include <string>

#include "layers/core/config_node.h"
#include "layers/core/memory.h"
#include "layers/train/compute_threads.h"
#include "layersnet.h"
#include "synthetic_scene.h"

namespace ln = layers::layersnet;

namespace {

// The device of LAYERS_BENCH_DEVICE (cpu when unset).
at::Device bench_device() {
  const char* d = std::getenv("LAYERS_BENCH_DEVICE");
  return at::Device(d && std::string(d) == "cuda" ? at::kCUDA : at::kCPU);
}

void move_input(layers::zoo::StepInput& in, const at::Device& device) {
  for (layers::zoo::GarmentState& g : in.garments) g = {g.prev.to(device), g.current.to(device)};
  for (at::Tensor* t : {&in.body, &in.body_next, &in.root, &in.root_rot, &in.wind_rotation, &in.wind_strength,
                        &in.joints, &in.joints_next})
    if (t->defined()) *t = t->to(device);
}

// Waits for the device (a no-op on the CPU) so that a step's time is all in.
void finish(const at::Tensor& out) {
  if (out.is_cuda())
    benchmark::DoNotOptimize(out.sum().item<float>());
  else
    benchmark::DoNotOptimize(out.data_ptr<float>());
}

struct Fixture {
  ln::testing::SyntheticScene scene;
  std::shared_ptr<ln::LayersNet> model;
  layers::zoo::StepInput input;
};

// Two garments of vertices/2 each, at about square cells (the garments are
// ~0.9-1.0 m round and 0.5 m high).
Fixture make_fixture(std::int64_t vertices, bool far_body) {
  ln::testing::SceneSize size;
  size.garment_rows = static_cast<int>(std::lround(std::sqrt(vertices / 2 / 1.9)));
  size.garment_cols = static_cast<int>(vertices / 2 / size.garment_rows);
  size.body_rows = 116;
  size.body_cols = 115;
  size.frames = 8;
  Fixture f{ln::testing::make_scene(size), nullptr, {}};
  at::manual_seed(0);
  f.model = std::dynamic_pointer_cast<ln::LayersNet>(ln::make_layersnet(layers::cfg::Node{}));
  f.model->set_normalization(ln::testing::scene_normalization(f.scene));
  f.model->to(bench_device());
  f.model->prepare(f.scene.statics);
  f.input = f.scene.input(5);  // wind blowing
  if (far_body) {
    const at::Tensor far = f.input.body + at::tensor({20.0f, 0.0f, 0.0f});
    f.input.body = at::cat({f.input.body, far});
    f.input.body_next = at::cat({f.input.body_next, far});
  }
  move_input(f.input, bench_device());
  return f;
}

void report(benchmark::State& state, const Fixture& f) {
  const ln::StepCounts& c = f.model->last_counts();
  state.counters["vertices"] = static_cast<double>(c.vertices);
  state.counters["body_vertices"] = static_cast<double>(f.input.body.size(0));
  state.counters["patches"] = static_cast<double>(c.patches);
  state.counters["body_tokens"] = static_cast<double>(c.body_tokens);
  state.counters["abstract"] = static_cast<double>(c.abstract_tokens);
  state.counters["mesh_edges"] = static_cast<double>(c.mesh_edges);
  state.counters["world_edges"] = static_cast<double>(c.world_edges);
  state.counters["body_edges"] = static_cast<double>(c.body_edges);
  state.counters["threads"] = static_cast<double>(at::get_num_threads());
}

void BM_LayersNetInference(benchmark::State& state) {
  Fixture f = make_fixture(state.range(0), state.range(1) != 0);
  at::NoGradGuard no_grad;
  for (auto _ : state) finish(f.model->step(f.input).garments[0]);
  report(state, f);
}

void BM_LayersNetTrainStep(benchmark::State& state) {
  Fixture f = make_fixture(state.range(0), false);
  std::vector<at::Tensor> target = f.scene.target(5);
  for (at::Tensor& t : target) t = t.to(bench_device());
  torch::optim::Adam adam(f.model->parameters(), torch::optim::AdamOptions(1e-3));
  for (auto _ : state) {
    adam.zero_grad();
    const layers::zoo::StepOutput out = f.model->step(f.input);
    at::Tensor loss =
        (out.garments[0] - target[0]).pow(2).sum(1).mean() + (out.garments[1] - target[1]).pow(2).sum(1).mean();
    loss.backward();
    adam.step();
    finish(loss);
  }
  report(state, f);
}

}  // namespace

BENCHMARK(BM_LayersNetInference)
    ->ArgNames({"vertices", "far_body"})
    ->Args({2000, 0})
    ->Args({8000, 0})
    ->Args({32000, 0})
    ->Args({8000, 1})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);
BENCHMARK(BM_LayersNetTrainStep)
    ->ArgNames({"vertices"})
    ->Arg(2000)
    ->Arg(8000)
    ->Unit(benchmark::kMillisecond)
    ->MinTime(2.0);

// One thread for the matrix products and torch's operators, as `run.threads:
// 1` gives a run, and freed memory kept for the next step, as in `layers`.
int main(int argc, char** argv) {
  layers::train::set_compute_threads(1);
  layers::keep_freed_memory();
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
