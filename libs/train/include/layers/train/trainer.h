// layers/train/trainer.h -- `layers train`: trains the experiment's model
// on its training split (torch-free API; the work is in trainer.cpp).
//
// Per optimiser step: a batch of windows; for each window the model first
// rolls min(epoch, curriculum_max) steps forward without gradient from the
// ground truth (the paper's rollout curriculum, docs/training.md; epoch counted
// from 0), then predicts t+1 (and t+2 from its own t+1 with two_step), and
// the weighted shared losses (frame_loss.h) plus the model's auxiliary
// losses are averaged over the batch. Adam, learning rate halved every
// lr_decay_every epochs by default, gradient norm clipping. After each
// epoch: validation rollouts (mean error in mm on the validation split)
// and checkpoints <run.output>/checkpoint-last.pt (always) and
// checkpoint-best.pt (best validation error). Deterministic for a seed and
// a thread count. A model without trainable parameters (static, skinned)
// is saved as is.
//
// Data-parallel (TrainOptions::group, layers/dist): every rank reads its
// slice of each epoch's windows (window_loader.h), gradients and batch
// losses are averaged over the ranks before clipping and the optimiser
// step, validation sequences are split over the ranks and their errors
// summed; rank 0 alone writes checkpoints, logs and the progress line. So
// N ranks at batch b step like one process at batch N*b on the same
// windows (tested), and a checkpoint resumes with any number of ranks.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "layers/train/experiment_config.h"

namespace layers::zoo {
class Registry;
}
namespace layers::dist {
class Group;
}

namespace layers::train {

struct TrainOptions {
  bool resume = false;  // continue from checkpoint-last.pt if present
  // Called once, just before the run's first file (a checkpoint) is
  // written: the model is made, a resumed checkpoint has loaded into it
  // (shapes checked) and the sequences read so far passed the integrity
  // check. Where a caller writes what must not change when the run cannot
  // start.
  std::function<void()> started;
  bool progress = true;          // progress line on stderr
  dist::Group* group = nullptr;  // data-parallel ranks (null: this process alone)
};

struct EpochSummary {
  int epoch = 0;  // 1-based
  double loss = 0;
  double val_error_mm = -1;  // < 0: no validation split
  double seconds = 0;
  double frames_per_second = 0;  // predicted training frames (with gradient) per second, all ranks
  double comm_seconds = 0;       // of `seconds`, in gradient exchanges (data-parallel)
  double data_seconds = 0;       // of `seconds`, waiting for the loader's next batch
  double optimizer_seconds = 0;  // of `seconds`, clipping gradients and the optimiser's step
  int ranks = 1;
  double lr = 0;
  double peak_resident_mib = 0;  // this process's peak resident memory so far (VmHWM)
  std::int64_t windows = 0;      // training windows of the epoch, all ranks
};

struct TrainReport {
  std::string run_dir;
  std::string last_checkpoint, best_checkpoint;
  std::vector<EpochSummary> epochs;  // epochs run now (not those resumed from)
  int epochs_done = 0;               // in total
  std::int64_t steps = 0;
  std::int64_t trainable_parameters = 0;
  double first_loss = 0;  // mean loss of the first batch run now
};

TrainReport run_training(const ExperimentConfig& config, const zoo::Registry& registry, const TrainOptions& options);

// <run.output>/checkpoint-<which>.pt
std::string checkpoint_path(const ExperimentConfig& config, const std::string& which);

}  // namespace layers::train
