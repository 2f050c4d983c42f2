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
// Errors are real-world millimetres (the paper's figures are at 10x
// scale). Collisions are the paper's vertex-normal H/L rates (L as the
// paper defines it, `l_collision_plain`, and ours with the open-edge rule,
// `l_collision`), crossings the exact H/L measures of geometry/intersect.h
// (docs/metrics.md). The ground truth's own rates are reported beside the
// model's.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/train/experiment_config.h"
#include "layers/zoo/metrics.h"

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
  bool progress = true;
  // Data-parallel ranks (layers/dist): each rolls out every size-th
  // sequence; rank 0 gathers the results in the split's order and alone
  // writes the outputs, equal to one process's. Null: this process alone.
  dist::Group* group = nullptr;
};

struct MetricSummary {
  zoo::MeanStd error_mm, h_collision, l_collision;  // rates as shares 0..1; l_collision: ours (open-edge rule)
  zoo::MeanStd h_crossing, l_crossing;              // exact crossings, shares 0..1
  zoo::MeanStd l_collision_plain;                   // the paper's L-collision (plain nearest vertex)
};

struct EvalReport {
  std::string model, checkpoint, split, out_dir;
  std::string checkpoint_kind, chosen_on;  // metrics.json's selection.checkpoint and .chosen_on
  std::int64_t sequences = 0, frames = 0, diverged = 0;
  MetricSummary overall;
  std::vector<std::pair<std::string, MetricSummary>> per_type;  // garment type -> summary
  double truth_h_collision = 0, truth_l_collision = 0;          // ground truth, mean over sequences
  double truth_h_crossing = 0, truth_l_crossing = 0;            // ground truth, mean over sequences
  double truth_l_collision_plain = 0;                           // ground truth, the paper's L-collision
  double ms_per_frame = 0;                                      // Model::step time per predicted frame
};

EvalReport run_evaluation(const ExperimentConfig& config, const zoo::Registry& registry, const EvalOptions& options);

// The checkpoint file EvalOptions::checkpoint names.
std::string resolve_checkpoint(const ExperimentConfig& config, const std::string& which);

}  // namespace layers::train
