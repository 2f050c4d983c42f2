// plugins/deepsd/src/graph_layer.h -- DeePSD's graph layer: a Linear over a
// vertex's own features and the mean of its mesh neighbours', then ReLU
// (its per-row MLPs are zoo::Mlp).
#pragma once

#include <ATen/ATen.h>
#include <torch/arg.h>
#include <torch/nn/module.h>
#include <torch/nn/modules/linear.h>
#include <torch/nn/pimpl.h>

#include <cstdint>

namespace layers::deepsd {

struct GarmentGraph;

struct GraphLayerOptions {
  GraphLayerOptions(std::int64_t in, std::int64_t out) : in_(in), out_(out) {}
  TORCH_ARG(std::int64_t, in);   // features per vertex in
  TORCH_ARG(std::int64_t, out);  // features per vertex out
};

class GraphLayerImpl : public torch::nn::Module {
 public:
  explicit GraphLayerImpl(const GraphLayerOptions& options);
  // h [V,in] -> relu(W [h, mean over neighbours of h] + b) [V,out].
  at::Tensor forward(const at::Tensor& h, const GarmentGraph& graph);

 private:
  torch::nn::Linear linear_{nullptr};
};

TORCH_MODULE(GraphLayer);

}  // namespace layers::deepsd
