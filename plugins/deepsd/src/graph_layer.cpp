// DeePSD's graph layer (see graph_layer.h).
#include "graph_layer.h"

#include <string>

#include "garment_graph.h"

namespace layers::deepsd {

GraphLayerImpl::GraphLayerImpl(const GraphLayerOptions& options) {
  linear_ = register_module("linear", torch::nn::Linear(2 * options.in(), options.out()));
}

at::Tensor GraphLayerImpl::forward(const at::Tensor& h, const GarmentGraph& graph) {
  return at::relu(linear_->forward(at::cat({h, mean_over_neighbours(h, graph)}, 1)));
}

}  // namespace layers::deepsd
