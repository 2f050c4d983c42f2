// LayersNet's patch decoder (see decoder.h).
#include "decoder.h"

namespace layers::layersnet {

Decoder::Decoder(std::int64_t vertex_features, std::int64_t width, std::int64_t outputs)
    : vertex_in_(register_module("vertex_in", torch::nn::Linear(vertex_features, width))),
      patch_in_(register_module("patch_in", torch::nn::Linear(torch::nn::LinearOptions(width, width).bias(false)))),
      hidden_(register_module("hidden", torch::nn::Linear(width, width))),
      out_(register_module("out", torch::nn::Linear(width, outputs))) {}

at::Tensor Decoder::forward(const at::Tensor& vertex_features, const at::Tensor& patches, const SceneTopology& t) {
  const at::Tensor first = vertex_in_->forward(vertex_features) + vertex_mean(t, patch_in_->forward(patches));
  return out_->forward(at::relu(hidden_->forward(at::relu(first))));
}

}  // namespace layers::layersnet
