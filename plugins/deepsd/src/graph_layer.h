// plugins/deepsd/src/graph_layer.h -- DeePSD's graph layer: a Linear over a
// vertex's own features and the mean of its mesh neighbours', then ReLU
// (its per-row MLPs are zoo::Mlp).
#pragma once

#include <ATen/ATen.h>
#include <torch/nn/module.h>
#include <torch/nn/modules/linear.h>

#include <cstdint>

namespace layers::deepsd {

struct GarmentGraph;

class GraphLayer : public torch::nn::Module {
 public:
  GraphLayer(std::int64_t in, std::int64_t out);
  // h [V,in] -> relu(W [h, mean over neighbours of h] + b) [V,out].
  at::Tensor forward(const at::Tensor& h, const GarmentGraph& graph);

 private:
  torch::nn::Linear linear_{nullptr};
};

}  // namespace layers::deepsd
