// Generator speed: seconds per simulated frame of the cloth solver for a
// two-layer outfit (a jumpsuit under a jacket) on the full MPFB2 body
// (13,380 vertices) walking (procedural walk), with strong wind, at about
// 1k, 4k and 16k garment vertices (edge lengths 50, 25 and 12.5 mm) with
// the 16 substeps of configs/data/small_tables.yaml, and at 5k vertices (22.5 mm)
// with 10 and 16 substeps, as `layers generate` runs it: one simulation
// alone (threads:1) and two side by side on two cores (threads:2, each
// thread its own scene, as with `--threads 2`). Set-up and warm-up (a
// short drape and blend) are not timed; each iteration is one recorded
// frame (1/30 s of motion). Arguments: edge length in tenths of a mm,
// substeps, contact passes as bits: 1 layer edge-edge (6 mm), 2 body
// edge-edge (2 mm), 4 the continuous-collision pass, 8 body edges on every
// 4th substep only (7: the defaults; 15: tiny.yaml's recipe; each
// resolution runs with and without the pass and with 15, the 25 mm scene
// also without body edges to price them).
// Counters: garment vertices, the solver's own split of the time per frame
// (per thread), the strain cap's sweeps per frame, and the generator's
// validation measures over the timed frames (measured outside the timing):
// mean H- and L-penetration (%), mean exact H- and L-crossing (%) and max
// edge stretch (%), and the most crossing face pairs between garments in
// any timed frame (cloth_x).
#include <benchmark/benchmark.h>

#include <string>

#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"
#include "layers/sim/measures.h"

namespace gen = layers::generate;

namespace {

// The scene of one benchmark thread: the given edge length and substeps,
// the settings of configs/data/small_tables.yaml otherwise (2 iterations).
gen::SceneSimulation make_scene(double edge_mm, int substeps, int frames, int edge_contact) {
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
  config.sim.substeps = substeps;
  config.sim.iterations = 2;
  if ((edge_contact & 1) == 0) config.sim.layer_edge_thickness = 0;
  if ((edge_contact & 2) == 0) config.sim.body_edge_thickness = 0;
  config.sim.collision_pass = (edge_contact & 4) != 0;
  if ((edge_contact & 8) != 0) config.sim.body_edge_every = 4;
  gen::SceneSpec spec = gen::sample_scene(config, 0);
  spec.shape = {};  // the average body
  return gen::SceneSimulation(config, spec);
}

void BM_GeneratorFrame(benchmark::State& state) {
  const double edge_mm = 0.1 * static_cast<double>(state.range(0));
  const int frames = static_cast<int>(state.max_iterations);
  // Third argument: bit 0 layer edges, bit 1 body edges, bit 2 the collision
  // pass, bit 3 body edges every 4th substep.
  const int edge_contact = static_cast<int>(state.range(2));
  gen::SceneSimulation scene = make_scene(edge_mm, static_cast<int>(state.range(1)), frames, edge_contact);
  if (!scene.usable()) {
    state.SkipWithError(scene.problem().c_str());
    return;
  }
  scene.warm_up();
  layers::sim::Solver& solver = scene.solver();
  solver.reset_timings();
  layers::sim::SequenceMeasures measures;  // validation measures, not timed
  int r = 0;
  for (auto _ : state) {
    scene.record(r++);
    state.PauseTiming();
    measures.add(layers::sim::measure_frame(solver));
    state.ResumeTiming();
  }
  int vertices = 0;
  for (int c = 0; c < solver.num_cloths(); ++c) vertices += solver.cloth(c).num_vertices();
  const layers::sim::StepTimings& t = solver.timings();
  // Per frame, averaged over the threads (each thread simulates its own scene).
  const auto per_frame_ms = [&](double seconds) {
    return benchmark::Counter(1e3 * seconds / static_cast<double>(t.frames), benchmark::Counter::kAvgThreads);
  };
  state.counters["garment_vertices"] = benchmark::Counter(vertices, benchmark::Counter::kAvgThreads);
  state.counters["elastic_ms"] = per_frame_ms(t.elastic);
  state.counters["layer_ms"] = per_frame_ms(t.layer_contact);
  state.counters["body_ms"] = per_frame_ms(t.body_contact);
  state.counters["self_ms"] = per_frame_ms(t.self_contact);
  state.counters["cap_ms"] = per_frame_ms(t.strain_cap);
  state.counters["pass_ms"] = per_frame_ms(t.collision_pass);
  state.counters["cloth_x"] =
      benchmark::Counter(static_cast<double>(measures.max_cloth_crossings()), benchmark::Counter::kAvgThreads);
  state.counters["H_pct"] = benchmark::Counter(100 * measures.mean_h_penetration(), benchmark::Counter::kAvgThreads);
  state.counters["L_pct"] = benchmark::Counter(100 * measures.mean_l_penetration(), benchmark::Counter::kAvgThreads);
  state.counters["Lx_pct"] = benchmark::Counter(100 * measures.mean_l_crossing(), benchmark::Counter::kAvgThreads);
  state.counters["Hx_pct"] = benchmark::Counter(100 * measures.mean_h_crossing(), benchmark::Counter::kAvgThreads);
  state.counters["stretch_pct"] = benchmark::Counter(100 * measures.max_stretch(), benchmark::Counter::kAvgThreads);
  state.counters["cand_builds"] = benchmark::Counter(
      static_cast<double>(t.candidate_builds) / static_cast<double>(t.frames), benchmark::Counter::kAvgThreads);
  state.counters["cand_body"] = benchmark::Counter(
      static_cast<double>(t.candidate_body_builds) / static_cast<double>(t.frames), benchmark::Counter::kAvgThreads);
  state.counters["cand_local"] = benchmark::Counter(
      static_cast<double>(t.candidate_refreshes) / static_cast<double>(t.frames), benchmark::Counter::kAvgThreads);
  state.counters["cand_pairs"] = benchmark::Counter(
      static_cast<double>(t.candidate_pairs) / static_cast<double>(t.frames), benchmark::Counter::kAvgThreads);
  state.counters["cap_sweeps"] = benchmark::Counter(static_cast<double>(t.cap_sweeps) / static_cast<double>(t.frames),
                                                    benchmark::Counter::kAvgThreads);
}

// Iterations are fixed (frames of the walk to record); wall time, since two
// threads run at once.
BENCHMARK(BM_GeneratorFrame)
    ->Args({500, 16, 7})
    ->Args({500, 16, 15})
    ->Args({500, 16, 3})
    ->Iterations(30)
    ->Threads(1)
    ->Threads(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_GeneratorFrame)
    ->Args({250, 16, 7})
    ->Args({250, 16, 15})
    ->Args({250, 16, 3})
    ->Iterations(20)
    ->Threads(1)
    ->Threads(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_GeneratorFrame)
    ->Args({125, 16, 7})
    ->Args({125, 16, 15})
    ->Args({125, 16, 3})
    ->Iterations(8)
    ->Threads(1)
    ->Threads(2)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_GeneratorFrame)
    ->Args({225, 10, 7})
    ->Iterations(20)
    ->Threads(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
BENCHMARK(BM_GeneratorFrame)
    ->Args({225, 16, 7})
    ->Iterations(20)
    ->Threads(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// Fewer substeps with tiny.yaml's recipe (the pass on, body edges every
// 4th substep): what each costs and what it does to stretch and crossings.
BENCHMARK(BM_GeneratorFrame)
    ->Args({250, 12, 15})
    ->Args({250, 8, 15})
    ->Iterations(20)
    ->Threads(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();
// The cost of edge-edge contact: the 25 mm scene with the pass and without
// body edges, and without the pass: without body edges, and without any.
BENCHMARK(BM_GeneratorFrame)
    ->Args({250, 16, 5})
    ->Args({250, 16, 1})
    ->Args({250, 16, 0})
    ->Iterations(20)
    ->Threads(1)
    ->Unit(benchmark::kMillisecond)
    ->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
