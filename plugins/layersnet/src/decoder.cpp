// LayersNet's patch decoder (see decoder.h).
#include "decoder.h"

namespace layers::layersnet {

DecoderImpl::DecoderImpl(const DecoderOptions& options)
    : vertex_in_(register_module("vertex_in", torch::nn::Linear(options.vertex_features(), options.width()))),
      patch_in_(register_module(
          "patch_in", torch::nn::Linear(torch::nn::LinearOptions(options.width(), options.width()).bias(false)))),
      hidden_(register_module("hidden", torch::nn::Linear(options.width(), options.width()))),
      out_(register_module("out", torch::nn::Linear(options.width(), options.outputs()))) {}

at::Tensor DecoderImpl::forward(const at::Tensor& vertex_features, const at::Tensor& patches, const SceneTopology& t) {
  const at::Tensor first = vertex_in_->forward(vertex_features) + vertex_mean(t, patch_in_->forward(patches));
  return out_->forward(at::relu(hidden_->forward(at::relu(first))));
}

}  // namespace layers::layersnet
