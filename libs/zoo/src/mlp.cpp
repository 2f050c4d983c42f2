// The shared multilayer perceptron (see mlp.h).
#include "layers/zoo/mlp.h"

namespace layers::zoo {

MlpImpl::MlpImpl(MlpOptions options) : options_(std::move(options)) {
  std::vector<std::int64_t> sizes = options_.hidden();
  sizes.push_back(options_.out());
  std::int64_t width = options_.in();
  for (std::size_t i = 0; i < sizes.size(); ++i) {
    layers_.push_back(register_module(options_.layer_prefix() + std::to_string(i), torch::nn::Linear(width, sizes[i])));
    width = sizes[i];
  }
}

at::Tensor MlpImpl::forward(at::Tensor x) {
  for (std::size_t i = 0; i < layers_.size(); ++i) {
    x = layers_[i]->forward(x);
    if (i + 1 < layers_.size()) x = at::relu(x);
  }
  return x;
}

}  // namespace layers::zoo
