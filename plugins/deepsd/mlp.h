// plugins/deepsd/mlp.h -- the two kinds of layer stacks DeePSD is made of:
// a per-row MLP (Linear layers with ReLU between them, none after the
// last) and a graph layer (a Linear over a vertex's own features and the
// mean of its mesh neighbours', then ReLU).
#pragma once

#include <ATen/ATen.h>
#include <torch/nn/module.h>
#include <torch/nn/modules/linear.h>

#include <cstdint>
#include <vector>

namespace layers::deepsd {

struct GarmentGraph;

class Mlp : public torch::nn::Module {
 public:
  // in -> hidden... -> out.
  Mlp(std::int64_t in, const std::vector<int>& hidden, std::int64_t out);
  at::Tensor forward(at::Tensor x);
  // The output layer (tests force it; the model may re-initialise it).
  torch::nn::Linear& last() { return layers_.back(); }
  std::int64_t out_features() const { return out_; }

 private:
  std::vector<torch::nn::Linear> layers_;
  std::int64_t out_;
};

class GraphLayer : public torch::nn::Module {
 public:
  GraphLayer(std::int64_t in, std::int64_t out);
  // h [V,in] -> relu(W [h, mean over neighbours of h] + b) [V,out].
  at::Tensor forward(const at::Tensor& h, const GarmentGraph& graph);

 private:
  torch::nn::Linear linear_{nullptr};
};

}  // namespace layers::deepsd
