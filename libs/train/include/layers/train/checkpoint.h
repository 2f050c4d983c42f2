// layers/train/checkpoint.h -- one self-contained checkpoint file: the
// model's parameters and buffers, its normalisation statistics, the
// optimiser state and the training position (epoch, step, best validation
// error). Written to a temporary name and renamed, so a crash never leaves
// a broken checkpoint behind. The file is a header line
// "layers-checkpoint 1 fnv1a64 <hash> <size>" and the torch archive the
// hash covers; loading verifies it (docs/training.md, "Checkpoints").
#pragma once

#include <cstdint>
#include <string>

namespace torch::optim {
class Optimizer;
}

namespace layers::zoo {
class Model;
}

namespace layers::train {

struct CheckpointState {
  int epochs_done = 0;
  std::int64_t steps = 0;
  double best_val_mm = -1;  // < 0: no validation yet
  std::string model_name;   // the registered model it belongs to
  std::string checksum;     // on load: the verified fnv1a64 of the archive ("" for one without)
};

// `optimizer` may be null (nothing to train, or an evaluation copy).
void save_checkpoint(const std::string& path, zoo::Model& model, const torch::optim::Optimizer* optimizer,
                     const CheckpointState& state);
// Restores into `model` (and `optimizer` when given). InputError naming the
// file, on one line, for a missing, damaged (checksum), unreadable
// checkpoint or one made for another model. A bare torch archive (written
// before checksums) is read unchecked, with a warning.
CheckpointState load_checkpoint(const std::string& path, zoo::Model& model, torch::optim::Optimizer* optimizer);

}  // namespace layers::train
