// layers/train/bench.h -- `layers bench`: inference and training speed of
// an experiment's model on a real scene of its dataset, scaled up by
// midpoint subdivision of the garments (about 4x vertices per level), and
// with the body doubled by a far-away copy (cost must follow the particles
// that matter, so that copy should change nothing). Timed with Google
// Benchmark; torch-free API.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "layers/core/config.h"
#include "layers/train/experiment_config.h"

namespace layers::zoo {
class Registry;
}

namespace layers::train {

// The defaults are those of `layers bench`; a study's `bench:` section
// starts from its own (layers/study/config.h, study_bench()). The keys of
// visit() are what a study file may set; sequence, split, out and
// checkpoint are set by `layers bench` flags (a study sets split to the
// split its run is evaluated on and checkpoint to the one its evaluation
// reads, and writes <run>/bench.json).
// Our simulator timed on a scene (`layers bench --simulator`).
struct SimulatorTiming {
  std::int64_t garment_vertices = 0;
  double ms_per_frame = 0;  // wall clock per recorded frame, one thread
};

struct BenchOptions {
  std::string sequence;   // default: the first sequence of `split`
  std::string split;      // default: eval.split, else data.test_split
  int levels = 2;         // subdivision levels 0..levels
  bool far_body = true;   // also measure with the far body copy
  bool train = true;      // also time a training step (forward + losses + backward)
  double min_time = 0.5;  // seconds per measurement
  // Also profile (bench.json rows' `profile`): where the time of an
  // inference and of a training step goes, by phase and operator, over
  // `profile_steps` steps of each scene without the far body, beside the
  // machine's matrix-product peak (`matmul_peak_gflops`).
  bool profile = false;
  int profile_steps = 5;
  std::string out;  // JSON file (default <run.output>/bench.json)
  // best, last (the run's own; missing: the model's initial weights, which
  // time the same) or a checkpoint file, which must exist (a study sets its
  // run's checkpoint, a lent one included).
  std::string checkpoint = "best";
  // Also time our simulator on the same scene at each level (rows without
  // the far body): called with the dataset folder, the sequence id and the
  // level. Empty: not timed. Set by the application, which knows the
  // generator (libs/train does not).
  std::function<SimulatorTiming(const std::string& dataset, const std::string& sequence, int level)> simulator;

  template <class V>
  void visit(V& v) {
    v("levels", levels, cfg::opt().range(0, 4).help("subdivision levels 0..n"));
    v("min_time", min_time, cfg::opt().range(0.01, 60).help("seconds per measurement"));
    v("train", train, cfg::opt().help("also time a training step"));
    v("far_body", far_body, cfg::opt().help("also time with a far-away body copy"));
  }
};

struct BenchRow {
  int level = 0;
  bool far_body = false;
  std::int64_t garment_vertices = 0, body_vertices = 0;
  std::map<std::string, double> counters;  // Model::step_counters()
  double ms_per_frame = 0;                 // inference, batch 1
  double train_ms_per_frame = 0;           // 0 when not measured or nothing to train
  // --profile: ms per step by phase (largest first) of an inference and a
  // training step; empty when not profiled.
  std::vector<std::pair<std::string, double>> infer_phases, train_phases;
  double infer_gflops = 0, train_gflops = 0;  // the profiler's flop count over the step's time
  SimulatorTiming simulator;                  // when timed (garment_vertices > 0)
};

struct BenchReport {
  std::string model, sequence, out;
  std::string split;       // the split `sequence` was taken from ("" when given by --sequence)
  std::string checkpoint;  // the checkpoint file loaded ("" = the model's initial weights)
  std::int64_t parameters = 0;
  int threads = 0;
  std::vector<BenchRow> rows;
  double matmul_peak_gflops = 0;  // --profile: a 1024 x 1024 product on these threads
  double peak_resident_mib =
      0;  // the process's peak resident memory after the model's timings (VmHWM; before --simulator)
};

BenchReport run_bench(const ExperimentConfig& config, const zoo::Registry& registry, const BenchOptions& options);

}  // namespace layers::train
