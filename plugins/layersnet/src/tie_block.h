// plugins/layersnet/src/tie_block.h -- one LayersNet processor block: TIE
// attention of the patch tokens over their senders (patches, abstract
// tokens, nearby body tokens), then a feed-forward network, each with a
// post-norm residual:
//   x = LN(x + Wo attn(x));  x = LN(x + W2 relu(W1 x))   (width -> 2 width -> width)
// Only patch tokens are updated; body and abstract tokens are senders whose
// embeddings stay as encoded (each block maps them with its own sender map).
#pragma once

#include <cstdint>

#include <torch/arg.h>
#include <torch/nn/module.h>
#include <torch/nn/modules/linear.h>
#include <torch/nn/modules/normalization.h>
#include <torch/nn/pimpl.h>

namespace layers::layersnet {

// Who sends to whom, for G = 2 head groups (0: mesh edges E^M, 1: world
// edges E^W); see docs/layersnet.md.
struct SenderGraph {
  at::Tensor dense_mask;  // [2,P,P+A]: patches, then abstract tokens
  at::Tensor body_slot;   // [P,K] int64 rows of the body tokens (any valid row where unused)
  at::Tensor body_mask;   // [2,P,K]
};

struct TieBlockOptions {
  TieBlockOptions(std::int64_t width, std::int64_t heads) : width_(width), heads_(heads) {}
  TORCH_ARG(std::int64_t, width);  // token width d
  TORCH_ARG(std::int64_t, heads);  // attention heads: half E^M, half E^W
};

class TieBlockImpl : public torch::nn::Module {
 public:
  explicit TieBlockImpl(const TieBlockOptions& options);
  // One block over the patch tokens; returns the patches [P,d].
  //   patches   [P,d] patch tokens (receivers)
  //   abstract  [A,d] gravity, wind and attribute tokens
  //   body      [B,d] body sender tokens
  at::Tensor forward(const at::Tensor& patches, const at::Tensor& abstract, const at::Tensor& body,
                     const SenderGraph& graph);

 private:
  std::int64_t heads_;
  torch::nn::Linear receiver_, sender_, query_, key_, value_, out_, ffn_in_, ffn_out_;
  torch::nn::LayerNorm norm_attn_, norm_ffn_;
};

TORCH_MODULE(TieBlock);

}  // namespace layers::layersnet
