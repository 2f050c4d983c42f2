// MLP and graph layers of DeePSD (see mlp.h).
#include "mlp.h"

#include <string>

#include "garment_graph.h"

namespace layers::deepsd {

Mlp::Mlp(std::int64_t in, const std::vector<int>& hidden, std::int64_t out) : out_(out) {
  std::int64_t width = in;
  std::vector<std::int64_t> sizes(hidden.begin(), hidden.end());
  sizes.push_back(out);
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    layers_.push_back(register_module(std::to_string(i), torch::nn::Linear(width, sizes[i])));
    width = sizes[i];
  }
}

at::Tensor Mlp::forward(at::Tensor x) {
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    x = layers_[i]->forward(x);
    if (i + 1 < layers_.size()) x = at::relu(x);
  }
  return x;
}

GraphLayer::GraphLayer(std::int64_t in, std::int64_t out) {
  linear_ = register_module("linear", torch::nn::Linear(2 * in, out));
}

at::Tensor GraphLayer::forward(const at::Tensor& h, const GarmentGraph& graph) {
  return at::relu(linear_->forward(at::cat({h, mean_over_neighbours(h, graph)}, 1)));
}

}  // namespace layers::deepsd
