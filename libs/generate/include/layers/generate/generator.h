// layers/generate/generator.h -- `layers generate`: a whole dataset folder
// from a generator config.
//
// Scene i goes to shard i / sequences_per_shard. Each finished scene is
// kept at once as parts/<id>.h5 (or parts/<id>.skipped with the reasons it
// failed validation), so an interrupted run resumes where it stopped; when
// every scene of a shard is done, its parts are merged into
// shard-NNNNN.h5 (atomically) and removed; a shard "exists" once that
// file does. `--shard k/n` (shard.h) makes this process do only the
// shards j with j % n == k, so several processes or machines can share
// the work. finalize_dataset() writes dataset.yaml, splits.yaml
// (train/val/test and the T, T+W, L, L+W subsets) and stats.h5 (train
// split only) once every shard exists: a generate run calls it at its end
// (unless told not to), and `layers generate --finalize` calls it alone,
// e.g. as a batch scheduler's job after the shards' jobs. The resolved
// config is saved as generator.yaml; resuming or finalizing with a
// different config is an error.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/generate/generator_config.h"

namespace layers::generate {

struct GenerateOptions {
  std::string out;      // dataset folder
  int shard_index = 0;  // k of --shard k/n
  int shard_count = 1;  // n
  int threads = 1;      // scenes simulated in parallel
  bool progress = true;
  bool finalize = true;  // finalize_dataset() at the end (when every shard exists)
  // A folder for refused scenes (empty: none kept): each as <id>.h5, a
  // shard of its recorded frames up to and including the one that broke a
  // rule (`layers export <folder>/<id>.h5 <id> --format glb`), and
  // <id>.refused.yaml: the rules broken, the frame, the motion.
  std::string keep_refused;
};

struct GenerateReport {
  int scenes = 0;                         // scenes of this process's shards
  int simulated = 0;                      // simulated by this run
  int reused = 0;                         // found finished (resume)
  int written = 0, skipped = 0;           // of those simulated now
  int cut = 0;                            // of those written: cut to a clean window (window_min_frames)
  std::vector<std::string> skip_reasons;  // "<id> (<motion family>): <reason>"
  int simulated_frames = 0;
  double simulate_seconds = 0;      // summed over scenes (all threads), wall clock
  double simulate_cpu_seconds = 0;  // the same in CPU time of the simulating threads
  double seconds = 0;               // wall clock
  bool finalized = false;           // dataset.yaml, splits.yaml (and stats.h5, below) written
  bool stats = false;               // stats.h5 written (false when the train split is empty)
};

struct FinalizeReport {
  int shards = 0;            // of the whole dataset
  std::vector<int> missing;  // shards not present (ascending); nothing was written then
  std::int64_t sequences = 0, frames = 0;
  bool stats = false;  // stats.h5 written (false when the train split is empty)
  bool done() const { return missing.empty(); }
};

// InputError (naming --out) unless `out` is new, an empty folder, or a
// folder a generation started (it holds generator.yaml; whether the config
// is the same is checked by generate_dataset). Nothing a user put in a
// folder is replaced by a dataset.
void check_output_folder(const std::string& out);

// `config_yaml` is the resolved config (saved and compared on resume).
GenerateReport generate_dataset(const GeneratorConfig& config, const std::string& config_yaml,
                                const GenerateOptions& options);

// dataset.yaml, splits.yaml and stats.h5 of the dataset folder `out` when
// every shard exists (a shard whose scenes are all finished but not yet
// merged is merged first); otherwise writes nothing and lists the missing
// shards. InputError when `out` holds no generator.yaml or one saved from
// another config than `config_yaml`. Writing the same shards again gives
// the same bytes, so finalizing twice is harmless.
FinalizeReport finalize_dataset(const GeneratorConfig& config, const std::string& config_yaml, const std::string& out);

// Whether `folder` holds every file a finished generate_dataset(config)
// leaves: all shards, splits.yaml, dataset.yaml and (when the train split
// is not empty) stats.h5. Says nothing about which config made them.
bool dataset_complete(const std::string& folder, const GeneratorConfig& config);

}  // namespace layers::generate
