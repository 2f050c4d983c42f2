// DeePSD's graph layer (see graph_layer.h).
#include "graph_layer.h"

#include <string>

#include "garment_graph.h"

namespace layers::deepsd {

GraphLayer::GraphLayer(std::int64_t in, std::int64_t out) {
  linear_ = register_module("linear", torch::nn::Linear(2 * in, out));
}

at::Tensor GraphLayer::forward(const at::Tensor& h, const GarmentGraph& graph) {
  return at::relu(linear_->forward(at::cat({h, mean_over_neighbours(h, graph)}, 1)));
}

}  // namespace layers::deepsd
