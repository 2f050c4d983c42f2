// layers/train/evaluator.h -- `layers eval`: rollouts of a trained model on
// a split with the metrics of docs/metrics.md, per sequence, per
// garment type and overall (torch-free API).
//
// Writes into the output folder (default <run.output>/eval-<split>):
//   metrics.json     everything: settings, overall, per type, per sequence,
//                    error, collision and crossing by rollout step (charts)
//   sequences.csv    one row per sequence and garment
//   predictions.h5   the rollouts as LAYERS-H5 (ground-truth body and wind,
//                    predicted garments; frames 0 and 1 are the ground truth
//                    the rollout started from) -- `layers export` reads it
// metrics.json's `selection` says what chose the checkpoint: `checkpoint`
// (best, last; unknown for another file saved before the record),
// `chosen_on` (the split whose validation error chose it; none for the
// last checkpoint or a run without validation; unknown for a checkpoint
// saved before the record), `evaluated_on`, `chosen_epoch`, `epochs`,
// `metric`. A checkpoint chosen on data.test_split is refused (InputError);
// one evaluated on the split that chose it is evaluated with a warning
// (its figures are optimistic; `layers report` marks it).
// Every metric of the registry (layers/metrics/registry.h) is measured,
// aggregated and written by the rules it declares: overall, per garment
// type, per sequence and garment, by rollout step, and for the ground
// truth where the metric asks. Errors are real-world millimetres (the
// paper's figures are at 10x scale).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "layers/metrics/measures.h"
#include "layers/train/experiment_config.h"

namespace layers::zoo {
class Registry;
}
namespace layers::dist {
class Group;
}

namespace layers::train {

struct EvalOptions {
  std::string checkpoint = "best";     // best, last, or a file path
  std::string split;                   // overrides eval.split
  int horizon = -1;                    // overrides eval.horizon when >= 0
  std::string out_dir;                 // default <run.output>/eval-<split>
  std::vector<std::string> sequences;  // only these ids (default: the whole split)
  // Another dataset's sequences (default: data.dataset's), normalised with
  // the training dataset's stats.h5: `layers animate --model`.
  std::string dataset;
  bool progress = true;
  // Data-parallel ranks (layers/dist): each rolls out every size-th
  // sequence; rank 0 gathers the results in the split's order and alone
  // writes the outputs, equal to one process's. Null: this process alone.
  dist::Group* group = nullptr;
};

// Every registered metric's mean +- std over sequences, by key
// (layers/metrics/registry.h); count 0: no sequence measured it.
using MetricSummary = std::map<std::string, metrics::MeanStd>;

struct EvalReport {
  std::string model, checkpoint, split, out_dir;
  std::string checkpoint_kind, chosen_on;  // metrics.json's selection.checkpoint and .chosen_on
  std::int64_t sequences = 0, frames = 0, diverged = 0;
  MetricSummary overall;
  std::vector<std::pair<std::string, MetricSummary>> per_type;  // garment type -> summary
  MetricSummary truth;                                          // the ground truth's, for MetricDef::truth metrics
  double ms_per_frame = 0;                                      // Model::step time per predicted frame
};

EvalReport run_evaluation(const ExperimentConfig& config, const zoo::Registry& registry, const EvalOptions& options);

// The checkpoint file EvalOptions::checkpoint names.
std::string resolve_checkpoint(const ExperimentConfig& config, const std::string& which);

}  // namespace layers::train
