// `layers bench <experiment.yaml>`: inference and training speed of the
// experiment's model on a real scene scaled by subdivision (see
// libs/train/include/layers/train/bench.h); writes <run.output>/bench.json.
#include <cmath>
#include <cstdio>

#include "config_loading.h"
#include "layers/generate/resimulate.h"
#include "layers/train/bench.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_bench(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("bench", "Time a model: ms per frame at batch 1 on scaled scenes, training speed");
  struct Args {
    ConfigArgs config;
    train::BenchOptions options;
    bool no_far = false, no_train = false, simulator = false;
    int simulator_frames = 4;
  };
  auto a = std::make_shared<Args>();
  add_config_options(*cmd, a->config, /*required=*/true);
  cmd->add_option("--sequence", a->options.sequence, "scene to scale (default: the first of --split)");
  cmd->add_option("--split", a->options.split,
                  "split the default scene comes from (default: eval.split, else the test split)");
  cmd->add_option("--levels", a->options.levels, "subdivision levels 0..n (x4 garment vertices each)")
      ->capture_default_str()
      ->check(CLI::Range(0, 4));
  cmd->add_option("--min-time", a->options.min_time, "seconds per measurement")->capture_default_str();
  cmd->add_option("--out", a->options.out, "JSON output (default <run.output>/bench.json)");
  cmd->add_option("--checkpoint", a->options.checkpoint,
                  "best, last (the run's own; initial weights when missing) or a checkpoint file")
      ->capture_default_str();
  cmd->add_flag("--no-far-body", a->no_far, "skip the runs with a far-away copy of the body");
  cmd->add_flag("--no-train", a->no_train, "time inference only");
  cmd->add_flag("--profile", a->options.profile,
                "also profile a step by phase and operator (bench.json rows' profile; docs/benchmarks.md)");
  cmd->add_option("--profile-steps", a->options.profile_steps, "steps profiled per scene")
      ->capture_default_str()
      ->check(CLI::Range(1, 1000));
  cmd->add_flag("--simulator", a->simulator,
                "also time our simulator on the same scene at each level (the dataset's generator config, edge "
                "length halved per level)");
  cmd->add_option("--simulator-frames", a->simulator_frames, "recorded frames the simulator runs per level")
      ->capture_default_str()
      ->check(CLI::Range(2, 1000));
  return [a]() {
    LoadedConfig loaded = load_config(a->config);
    a->options.far_body = !a->no_far;
    a->options.train = !a->no_train;
    if (a->simulator) {
      const int frames = a->simulator_frames;
      // Refused before any timing: no generator config, frames out of
      // range, or a finest level finer than the fit allows.
      generate::check_resimulation(loaded.typed.data.dataset, frames, std::ldexp(1.0, -a->options.levels));
      // One midpoint subdivision per level is about 4x the garment
      // vertices; half the fit's edge length is the simulator's same step.
      a->options.simulator = [frames](const std::string& dataset, const std::string& sequence, int level) {
        generate::ResimulateOptions o;
        o.edge_scale = std::ldexp(1.0, -level);
        o.keep_positions = false;
        const generate::Resimulation r = generate::resimulate(dataset, sequence, frames, o);
        return train::SimulatorTiming{r.garment_vertices, r.wall_ms_per_frame};
      };
    }
    const train::BenchReport r = train::run_bench(loaded.typed, load_plugins().registry, a->options);
    const std::string scene = r.split.empty() ? r.sequence : r.sequence + " (" + r.split + ")";
    std::printf("%s (%lld parameters, %d threads, %s) on %s\n", r.model.c_str(), static_cast<long long>(r.parameters),
                r.threads, r.checkpoint.empty() ? "initial weights" : r.checkpoint.c_str(), scene.c_str());
    std::printf("%5s %9s %9s %8s %12s %14s  %s\n", "level", "garment v", "body v", "far body", "infer ms/fr",
                "train ms/fr", "counters");
    for (const auto& row : r.rows) {
      std::string counters;
      for (const auto& [k, v] : row.counters) counters += k + "=" + std::to_string(static_cast<long long>(v)) + " ";
      std::printf("%5d %9lld %9lld %8s %12.2f %14.2f  %s\n", row.level, static_cast<long long>(row.garment_vertices),
                  static_cast<long long>(row.body_vertices), row.far_body ? "yes" : "no", row.ms_per_frame,
                  row.train_ms_per_frame, counters.c_str());
    }
    for (const auto& row : r.rows) {
      const auto phases = [](const char* what, const std::vector<std::pair<std::string, double>>& list, double gflops) {
        if (list.empty()) return;
        std::printf("  %s:", what);
        for (const auto& [name, ms] : list) std::printf(" %s %.2f ms,", name.c_str(), ms);
        std::printf(" %.1f GFLOP/s\n", gflops);
      };
      if (row.infer_phases.empty()) continue;
      std::printf("level %d profile (ms per step by phase):\n", row.level);
      phases("infer", row.infer_phases, row.infer_gflops);
      phases("train", row.train_phases, row.train_gflops);
    }
    for (const auto& row : r.rows) {
      if (row.simulator.garment_vertices == 0) continue;
      std::printf("level %d, our simulator: %lld garment vertices, %.1f ms/frame; simulator / model = %.1f\n",
                  row.level, static_cast<long long>(row.simulator.garment_vertices), row.simulator.ms_per_frame,
                  row.simulator.ms_per_frame / row.ms_per_frame);
    }
    std::printf("peak resident memory: %.0f MiB\n", r.peak_resident_mib);
    if (r.matmul_peak_gflops > 0) std::printf("matrix-product peak: %.1f GFLOP/s\n", r.matmul_peak_gflops);
    std::printf("written: %s\n", r.out.c_str());
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
