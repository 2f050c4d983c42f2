// layers/train/rollout.h -- autoregressive rollouts (docs/metrics.md):
// start from ground truth, feed predictions back, body and wind stay ground
// truth; every metric of the registry (layers/metrics/registry.h) per
// frame, also of the ground truth where the metric says so, and divergence
// detection: a non-finite prediction or a frame error above the bound
// stops the rollout and is recorded with its frame, never a crash. Frames
// after divergence count as each metric's registry entry says (the error
// as the bound: a diverged model cannot look better by stopping early;
// the rates left out).
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "layers/metrics/registry.h"
#include "layers/train/scene_tensors.h"

namespace layers::train {

struct RolloutOptions {
  std::int64_t start = 1;    // row of `frames` with the last ground-truth state
  std::int64_t steps = -1;   // predicted frames; < 0: to the end of `frames`
  double diverge_mm = 1000;  // error bound of divergence
  bool keep_predictions = false;
  bool truth_collisions = true;  // also measure the ground truth, for the metrics that ask (MetricDef::truth)
  bool rates = true;             // false: the error only, every other metric NaN (training's validation)
};

// One predicted frame: a value per registered metric, in registry order.
struct FrameMetrics {
  std::int64_t frame = 0;                  // absolute frame
  std::vector<metrics::FrameValue> value;  // the prediction's (scene NaN, no garments: not measured)
  std::vector<double> truth;               // the ground truth's scene values (NaN: not measured)
  bool diverged = false;                   // at or after divergence
  // The registry's error_mm: mean over all garment vertices.
  double error_mm() const;
};

struct RolloutResult {
  std::vector<FrameMetrics> frames;
  std::int64_t diverged_at = -1;  // absolute frame, -1 if stable
  std::string diverge_reason;
  std::vector<at::Tensor> predictions;  // [steps,V,3] per garment (keep_predictions)
  double model_seconds = 0;             // time spent in Model::step
};

// `model` must be prepared with `seq`; runs without gradients.
RolloutResult rollout(zoo::Model& model, const zoo::SequenceStatic& seq, const FrameTensors& frames,
                      const RolloutOptions& options);

}  // namespace layers::train
