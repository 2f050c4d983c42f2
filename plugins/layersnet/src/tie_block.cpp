// One LayersNet processor block (see tie_block.h).
#include "tie_block.h"

#include "layers/zoo/phase.h"
#include "tie_attention.h"

namespace layers::layersnet {

TieBlockImpl::TieBlockImpl(const TieBlockOptions& options)
    : heads_(options.heads()),
      receiver_(register_module("receiver", torch::nn::Linear(options.width(), options.width()))),
      sender_(register_module("sender", torch::nn::Linear(options.width(), options.width()))),
      query_(register_module("query", torch::nn::Linear(options.width(), options.width()))),
      key_(register_module("key", torch::nn::Linear(options.width(), options.width()))),
      value_(register_module("value", torch::nn::Linear(options.width(), options.width()))),
      out_(register_module("out", torch::nn::Linear(options.width(), options.width()))),
      ffn_in_(register_module("ffn_in", torch::nn::Linear(options.width(), 2 * options.width()))),
      ffn_out_(register_module("ffn_out", torch::nn::Linear(2 * options.width(), options.width()))),
      norm_attn_(register_module("norm_attn", torch::nn::LayerNorm(torch::nn::LayerNormOptions({options.width()})))),
      norm_ffn_(register_module("norm_ffn", torch::nn::LayerNorm(torch::nn::LayerNormOptions({options.width()})))) {}

at::Tensor TieBlockImpl::forward(const at::Tensor& patches, const at::Tensor& abstract, const at::Tensor& body,
                                 const SenderGraph& graph) {
  const zoo::Phase phase_attention("phase:attention");
  TieSenders senders;
  senders.dense = sender_->forward(at::cat({patches, abstract}, 0));
  senders.dense_mask = graph.dense_mask;
  const std::int64_t K = graph.body_slot.defined() ? graph.body_slot.size(1) : 0;
  if (K > 0 && body.size(0) > 0) {
    senders.local = sender_->forward(body);
    senders.local_index = graph.body_slot;
    senders.local_mask = graph.body_mask;
  }
  TieWeights w{key_->weight, key_->bias, value_->weight, value_->bias, heads_};
  const at::Tensor attended = tie_attention(query_->forward(patches), receiver_->forward(patches), senders, w);
  at::Tensor x = norm_attn_->forward(patches + out_->forward(attended));
  const zoo::Phase phase_block_mlp("phase:block_mlp");
  return norm_ffn_->forward(x + ffn_out_->forward(at::relu(ffn_in_->forward(x))));
}

}  // namespace layers::layersnet
