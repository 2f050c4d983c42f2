// LayersNet's MLP (see mlp.h).
#include "mlp.h"

#include <string>

namespace layers::layersnet {

Mlp::Mlp(std::int64_t in, std::int64_t hidden, std::int64_t out, int hidden_layers) {
  std::int64_t from = in;
  for (int i = 0; i <= hidden_layers; ++i) {
    const std::int64_t to = i == hidden_layers ? out : hidden;
    layers_.push_back(register_module("linear" + std::to_string(i), torch::nn::Linear(from, to)));
    from = to;
  }
}

at::Tensor Mlp::forward(at::Tensor x) {
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    x = layers_[i]->forward(x);
    if (i + 1 < layers_.size()) x = at::relu(x);
  }
  return x;
}

}  // namespace layers::layersnet
