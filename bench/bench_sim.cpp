// Generator speed: seconds per simulated frame of the cloth solver for a
// two-layer outfit (a jumpsuit under a jacket) on the full MPFB2 body
// (13,380 vertices) walking (procedural walk), with strong wind, at about
// 1k, 4k and 16k garment vertices (edge lengths 50, 25 and 12.5 mm), as
// `layers generate` runs it: one simulation alone (threads:1) and two side
// by side on two cores (threads:2, each thread its own scene, as with
// `--threads 2`). Set-up and warm-up (a short drape and blend) are not
// timed; each iteration is one recorded frame (1/30 s of motion). Counters:
// garment vertices, and the solver's own split of the time per frame.
#include <benchmark/benchmark.h>

#include <string>

#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"

namespace gen = layers::generate;

namespace {

// The scene of one benchmark thread: the given edge length, the settings
// of configs/data/small.yaml otherwise (16 substeps, 2 iterations).
gen::SceneSimulation make_scene(double edge_mm, int frames) {
  gen::GeneratorConfig config;
  config.name = "bench";
  config.seed = 3;
  config.frames = frames;
  config.drape_frames = 8;
  config.body.transition_frames = 6;
  config.body.motions = {"procedural:walk"};
  config.garments.fit.edge_length = edge_mm / 1000.0;
  config.garments.outfits = {gen::OutfitConfig{{"jumpsuit"}, "jacket", 1.0}};
  config.wind.calm_weight = config.wind.mixed_weight = 0;
  config.wind.strong_weight = 1;
  config.sim.substeps = 16;
  config.sim.iterations = 2;
  gen::SceneSpec spec = gen::sample_scene(config, 0);
  spec.shape = {};  // the average body
  return gen::SceneSimulation(config, spec);
}

void BM_GeneratorFrame(benchmark::State& state) {
  const double edge_mm = 0.1 * static_cast<double>(state.range(0));  // argument: tenths of a mm
  const int frames = static_cast<int>(state.max_iterations);
  gen::SceneSimulation scene = make_scene(edge_mm, frames);
  if (!scene.usable()) {
    state.SkipWithError(scene.problem().c_str());
    return;
  }
  scene.warm_up();
  layers::sim::Solver& solver = scene.solver();
  solver.reset_timings();
  int r = 0;
  for (auto _ : state) scene.record(r++);
  int vertices = 0;
  for (int c = 0; c < solver.num_cloths(); ++c) vertices += solver.cloth(c).num_vertices();
  const layers::sim::StepTimings& t = solver.timings();
  const double n = static_cast<double>(t.frames);
  state.counters["garment_vertices"] = vertices;
  state.counters["elastic_ms"] = 1e3 * t.elastic / n;
  state.counters["layer_contact_ms"] = 1e3 * t.layer_contact / n;
  state.counters["body_contact_ms"] = 1e3 * t.body_contact / n;
  state.counters["self_contact_ms"] = 1e3 * t.self_contact / n;
}

// Iterations are fixed (frames of the walk to record); wall time, since two
// threads run at once.
BENCHMARK(BM_GeneratorFrame)->Arg(500)->Iterations(30)->Threads(1)->Threads(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GeneratorFrame)->Arg(250)->Iterations(20)->Threads(1)->Threads(2)->Unit(benchmark::kMillisecond)->UseRealTime();
BENCHMARK(BM_GeneratorFrame)->Arg(125)->Iterations(8)->Threads(1)->Threads(2)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
