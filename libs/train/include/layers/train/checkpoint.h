// layers/train/checkpoint.h -- one self-contained checkpoint file: the
// model's parameters and buffers, its normalisation statistics, the
// optimiser state, the training position (epoch, step, best validation
// error) and what chose it (the selection record: which checkpoint, the
// split and epoch that chose it). Written to a temporary name and renamed, so a crash never leaves
// a broken checkpoint behind. The file is a header line
// "layers-checkpoint 1 fnv1a64 <hash> <size>" and the torch archive the
// hash covers; loading verifies it (docs/training.md, "Checkpoints").
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace torch::optim {
class Optimizer;
}

namespace layers::zoo {
class Model;
}

namespace layers::train {

// The largest checkpoint file read (1 GiB; ours are tens of MB): a larger
// file, a folder or a device is refused before anything is read.
constexpr std::uintmax_t kMaxCheckpointBytes = std::uintmax_t{1} << 30;

struct CheckpointState {
  int epochs_done = 0;
  std::int64_t steps = 0;
  double best_val_mm = -1;  // < 0: no validation yet
  std::string model_name;   // the registered model it belongs to
  std::string checksum;     // on load: the verified fnv1a64 of the archive ("" for one without)
  // The selection record (docs/training.md, "Selection").
  std::string kind;       // "best" or "last": which checkpoint this file was saved as
  std::string chosen_on;  // split whose validation error chose the best epoch ("" = nothing chosen)
  std::string metric;     // what was compared on it ("" = nothing chosen)
  int chosen_epoch = 0;   // epoch (1-based) of the best validation error (0 = none)
  int epochs = 0;         // train.epochs when it was saved
  bool recorded = false;  // on load: the file carries the record (false for one saved before it)
  // Per finished epoch (index = epoch - 1): mean training loss and
  // validation error (mm; -1: no validation). Empty for a checkpoint saved
  // before they were kept; NaN for the epochs a resumed training ran
  // before they were kept.
  std::vector<double> loss_by_epoch, val_mm_by_epoch;
  // Training windows seen in each finished epoch, all ranks (NaN where not
  // kept: epochs trained before it was recorded). The learning curves'
  // x axis (validation error against windows seen).
  std::vector<double> windows_by_epoch;
};

// `optimizer` may be null (nothing to train, or an evaluation copy).
void save_checkpoint(const std::string& path, zoo::Model& model, const torch::optim::Optimizer* optimizer,
                     const CheckpointState& state);
// Restores into `model` (and `optimizer` when given). InputError naming the
// file, on one line, for a missing, damaged (checksum), unreadable
// checkpoint, one made for another model, a folder, a special file or one
// over kMaxCheckpointBytes, or a bare torch archive without our checksum
// header.
CheckpointState load_checkpoint(const std::string& path, zoo::Model& model, torch::optim::Optimizer* optimizer);

}  // namespace layers::train
