// layers/train/rollout.h -- autoregressive rollouts (docs/metrics.md):
// start from ground truth, feed predictions back, body and wind stay ground
// truth; per-frame metrics (Euclidean error, the paper's vertex-normal H-
// and L-collision and our L-collision with its open-edge rule, the exact
// H- and L-crossing of geometry/intersect.h;
// also of the ground truth for reference) and divergence detection: a non-finite
// prediction or a frame error above the bound stops the rollout and is
// recorded with its frame, never a crash. Frames after divergence count
// with the bound as their error (a diverged model cannot look better by
// stopping early) and are left out of the collision and crossing rates.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "layers/train/scene_tensors.h"

namespace layers::train {

struct RolloutOptions {
  std::int64_t start = 1;    // row of `frames` with the last ground-truth state
  std::int64_t steps = -1;   // predicted frames; < 0: to the end of `frames`
  double diverge_mm = 1000;  // error bound of divergence
  bool keep_predictions = false;
  bool truth_collisions = true;  // also measure the ground truth's H/L collision and crossing rates
  bool rates = true;             // false: errors only, every rate NaN (training's validation)
};

struct FrameMetrics {
  std::int64_t frame = 0;                   // absolute frame
  double error_mm = 0;                      // mean over all garment vertices
  std::vector<double> garment_error_mm;     // per garment
  std::vector<double> garment_h_collision;  // per garment, share behind the body
  double h_collision = 0;                   // all garment vertices
  // L-collision, ours (open-edge rule) and the paper's (plain nearest
  // vertex): zoo/metrics.h. NaN: no inner+outer pair.
  double l_collision = std::numeric_limits<double>::quiet_NaN();
  double l_collision_plain = std::numeric_limits<double>::quiet_NaN();
  double truth_h_collision = std::numeric_limits<double>::quiet_NaN();
  double truth_l_collision = std::numeric_limits<double>::quiet_NaN();
  double truth_l_collision_plain = std::numeric_limits<double>::quiet_NaN();
  // Exact crossings (docs/metrics.md): share of garment vertices on faces
  // through the body, of outer vertices on faces through the inner layer.
  std::vector<double> garment_h_crossing;                        // per garment
  double h_crossing = 0;                                         // all garment vertices
  double l_crossing = std::numeric_limits<double>::quiet_NaN();  // NaN: no inner+outer pair
  double truth_h_crossing = std::numeric_limits<double>::quiet_NaN();
  double truth_l_crossing = std::numeric_limits<double>::quiet_NaN();
  bool diverged = false;  // after divergence: error = bound, collisions and crossings NaN
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
