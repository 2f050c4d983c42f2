// layers/zoo/mlp.h -- the multilayer perceptron the model plugins share
// (LayersNet's encoders, DeePSD's heads): Linear layers with ReLU between
// them and none after the last, built from MlpOptions and held by the
// TORCH_MODULE holder Mlp.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <torch/arg.h>
#include <torch/nn/module.h>
#include <torch/nn/modules/linear.h>
#include <torch/nn/pimpl.h>

namespace layers::zoo {

struct MlpOptions {
  MlpOptions(std::int64_t in, std::vector<std::int64_t> hidden, std::int64_t out)
      : in_(in), hidden_(std::move(hidden)), out_(out) {}
  TORCH_ARG(std::int64_t, in);
  // Widths of the hidden layers, in order (may be empty: one Linear).
  TORCH_ARG(std::vector<std::int64_t>, hidden);
  TORCH_ARG(std::int64_t, out);
  // Layer i is registered as layer_prefix + i: the names its parameters
  // have in checkpoints ("linear0.weight"; DeePSD's heads use "").
  TORCH_ARG(std::string, layer_prefix) = "linear";
};

class MlpImpl : public torch::nn::Module {
 public:
  explicit MlpImpl(MlpOptions options);
  // x [..., in] -> [..., out].
  at::Tensor forward(at::Tensor x);
  // The output layer (a model may re-initialise it; tests force it).
  torch::nn::Linear& last() { return layers_.back(); }
  const MlpOptions& options() const { return options_; }

 private:
  MlpOptions options_;
  std::vector<torch::nn::Linear> layers_;
};

TORCH_MODULE(Mlp);

}  // namespace layers::zoo
