// layers/zoo/normalization.h -- the training split's mean and standard
// deviation (stats.h5, see layers/data/stats.h) as tensors a model uses to
// normalise its inputs and to scale its outputs back.
//
// Positions are root-relative (p - root(t)); velocities and accelerations
// are per-frame differences. Each Moments pair holds a mean [3] and a std
// [3] in float32; normalize(x) = (x - mean) / std broadcasts over any
// leading dimensions. identity() (mean 0, std 1) is what a model has until
// the trainer or evaluator sets the dataset's.
#pragma once

#include <ATen/ATen.h>

#include "layers/data/stats.h"

namespace layers::zoo {

struct NormPair {
  at::Tensor mean;  // [3]
  at::Tensor std;   // [3]

  at::Tensor normalize(const at::Tensor& x) const { return (x - mean) / std; }
  at::Tensor denormalize(const at::Tensor& x) const { return x * std + mean; }
  // Scale only (for differences of quantities that share this mean).
  at::Tensor scale(const at::Tensor& x) const { return x / std; }
  at::Tensor unscale(const at::Tensor& x) const { return x * std; }
};

struct Normalization {
  NormPair garment_position, garment_velocity, garment_acceleration;
  NormPair body_position, body_velocity, body_acceleration;

  static Normalization identity();
  static Normalization from_stats(const data::NormStats& stats);
  // The same values on `device`.
  Normalization to(const at::Device& device) const;
};

}  // namespace layers::zoo
