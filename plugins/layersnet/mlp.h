// plugins/layersnet/mlp.h -- the multilayer perceptron LayersNet's
// encoders and decoder are made of: Linear layers with ReLU between them
// (none after the last).
#pragma once

#include <cstdint>
#include <vector>

#include <torch/nn/module.h>
#include <torch/nn/modules/linear.h>

namespace layers::layersnet {

class Mlp : public torch::nn::Module {
 public:
  // in -> hidden (x hidden_layers) -> out; hidden_layers >= 1.
  Mlp(std::int64_t in, std::int64_t hidden, std::int64_t out, int hidden_layers);
  at::Tensor forward(at::Tensor x);

 private:
  std::vector<torch::nn::Linear> layers_;
};

}  // namespace layers::layersnet
