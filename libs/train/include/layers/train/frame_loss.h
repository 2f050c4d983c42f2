// layers/train/frame_loss.h -- the weighted sum of the shared loss terms
// (layers/zoo/losses.h) on one predicted frame of every garment, with the
// weights of the experiment's `loss:` section. Distances enter in
// centimetres (position and collision terms are cm^2); the normal term is
// unitless, so a weight w at the paper's scale (lengths x10, squared
// lengths x100 of metres) is w x 100 here for the normal term and w for the
// squared-length terms (docs/reproduction.md, "Loss units").
#pragma once

#include <map>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "layers/train/experiment_config.h"
#include "layers/zoo/model.h"

namespace layers::train {

struct LossSum {
  at::Tensor total;                     // scalar, differentiable
  std::map<std::string, double> terms;  // unweighted values, for logs
};

// `pred` and `truth`: one [V,3] per garment of `seq`; `body`: [Vb,3] at the
// predicted frame.
LossSum frame_loss(const zoo::SequenceStatic& seq, const std::vector<at::Tensor>& pred,
                   const std::vector<at::Tensor>& truth, const at::Tensor& body, const LossConfig& weights);

}  // namespace layers::train
