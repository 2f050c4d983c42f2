// plugins/layersnet/src/decoder.h -- LayersNet's patch decoder: an MLP over
// each vertex's [own features, mean embedding of its patches] -> outputs
// (3: the normalised acceleration; a 4th: the base's blend logit),
// width -> width -> outputs with ReLUs.
//
// The first layer is linear in the concatenation, so its patch-embedding
// block is applied to the P patch tokens and then averaged to the
// vertices: W [f_v, sum_p w_vp x_p] = W_f f_v + sum_p w_vp (W_x x_p) -- the
// same map, with P instead of V products of width x width.
#pragma once

#include <cstdint>

#include <torch/arg.h>
#include <torch/nn/module.h>
#include <torch/nn/modules/linear.h>
#include <torch/nn/pimpl.h>

#include "topology.h"

namespace layers::layersnet {

struct DecoderOptions {
  DecoderOptions(std::int64_t vertex_features, std::int64_t width) : vertex_features_(vertex_features), width_(width) {}
  TORCH_ARG(std::int64_t, vertex_features);  // per-vertex input features f
  TORCH_ARG(std::int64_t, width);            // patch token width
  TORCH_ARG(std::int64_t, outputs) = 3;      // acceleration (3), plus a gate logit (4)
};

class DecoderImpl : public torch::nn::Module {
 public:
  explicit DecoderImpl(const DecoderOptions& options);
  // vertex_features [V,f], patches [P,width] -> [V,outputs].
  at::Tensor forward(const at::Tensor& vertex_features, const at::Tensor& patches, const SceneTopology& t);

 private:
  torch::nn::Linear vertex_in_, patch_in_, hidden_, out_;
};

TORCH_MODULE(Decoder);

}  // namespace layers::layersnet
