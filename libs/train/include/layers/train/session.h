// layers/train/session.h -- what training, evaluation and rollouts of one
// experiment share: the opened dataset, the model created from the config
// (on the configured device, normalised with the dataset's stats.h5),
// the garment selection, and the run's seed and thread count applied.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "layers/data/dataset.h"
#include "layers/train/experiment_config.h"
#include "layers/train/rollout.h"
#include "layers/train/scene_tensors.h"
#include "layers/zoo/model.h"

namespace layers::zoo {
class Registry;
}

namespace layers::train {

struct Session {
  ExperimentConfig config;
  data::Dataset dataset;
  std::shared_ptr<zoo::Model> model;
  GarmentSelection selection;
  at::Device device = at::Device(at::kCPU);
};

// InputError naming the config file for a missing data.dataset, an
// unknown model or bad parameters, or a CUDA device on a CPU-only build.
// `device_index` >= 0 picks the CUDA device (a data-parallel rank's LOCAL_RANK).
// `dataset` (when not empty) is where the sequences come from instead of
// data.dataset, e.g. a scene of `layers animate --model`; the
// normalisation is still the training dataset's stats.h5.
Session open_session(const ExperimentConfig& config, const zoo::Registry& registry, int device_index = -1,
                     const std::string& dataset = "");

// One rollout per sequence from its first frames: ground truth at frames 0
// and 1, then `horizon` predicted frames (0 or more than the sequence has:
// to its end). `rates` false: errors only (see RolloutOptions::rates).
struct SequenceRollout {
  std::string id;
  std::shared_ptr<const zoo::SequenceStatic> statics;
  FrameTensors frames;  // the ground truth of the rolled-out frames
  RolloutResult result;
};
SequenceRollout rollout_sequence(Session& session, const std::string& id, std::int64_t horizon, double diverge_mm,
                                 bool keep_predictions, bool rates = true);
// The same without the rollout (`result` left empty): what a rollout made
// elsewhere (another rank) needs beside its result.
SequenceRollout sequence_truth(Session& session, const std::string& id, std::int64_t horizon);

}  // namespace layers::train
