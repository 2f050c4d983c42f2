// layers/mgnet/uv_network.h -- MGNet's convolutional networks on UV
// images: an encoder (stride-2 3x3 convolutions, then a linear layer to a
// latent code) and a decoder (a linear layer back to the coarsest grid,
// stride-2 transposed convolutions up to R x R, a last 3x3 convolution to
// the output channels). SiLU between layers. Written on ATen ops with
// registered parameters (no torch::nn layer headers); initialised He-
// uniform from torch's global RNG, the decoder's last layer scaled down so
// that a fresh model predicts almost no displacement.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

#include <ATen/ATen.h>
#include <torch/arg.h>
#include <torch/nn/module.h>
#include <torch/nn/pimpl.h>

namespace layers::mgnet {

struct UvEncoderOptions {
  UvEncoderOptions(std::int64_t in_channels, std::vector<std::int64_t> channels, std::int64_t resolution,
                   std::int64_t latent)
      : in_channels_(in_channels), channels_(std::move(channels)), resolution_(resolution), latent_(latent) {}
  TORCH_ARG(std::int64_t, in_channels);
  TORCH_ARG(std::vector<std::int64_t>, channels);  // per stride-2 stage
  TORCH_ARG(std::int64_t, resolution);             // image side, divisible by 2^stages
  TORCH_ARG(std::int64_t, latent);
};

class UvEncoderImpl : public torch::nn::Module {
 public:
  // Images of `in_channels` x resolution x resolution; channels per stage
  // (resolution divisible by 2^stages, checked by read_params()).
  explicit UvEncoderImpl(const UvEncoderOptions& options);
  // [G,in,R,R] -> [G,latent]
  at::Tensor forward(const at::Tensor& images) const;

 private:
  std::vector<at::Tensor> weight_, bias_;
  at::Tensor head_weight_, head_bias_;
};

TORCH_MODULE(UvEncoder);

struct UvDecoderOptions {
  UvDecoderOptions(std::int64_t code_size, std::vector<std::int64_t> channels, std::int64_t resolution,
                   std::int64_t out_channels)
      : code_size_(code_size), channels_(std::move(channels)), resolution_(resolution), out_channels_(out_channels) {}
  TORCH_ARG(std::int64_t, code_size);
  TORCH_ARG(std::vector<std::int64_t>, channels);  // the mirrored encoder's stages
  TORCH_ARG(std::int64_t, resolution);
  TORCH_ARG(std::int64_t, out_channels);
};

class UvDecoderImpl : public torch::nn::Module {
 public:
  // A code of `code_size` -> `out_channels` x resolution x resolution,
  // mirroring an encoder with these stage channels.
  explicit UvDecoderImpl(const UvDecoderOptions& options);
  // [G,code] -> [G,out,R,R]
  at::Tensor forward(const at::Tensor& code) const;

 private:
  std::int64_t coarse_ = 0;  // side of the coarsest grid
  at::Tensor head_weight_, head_bias_;
  std::vector<at::Tensor> weight_, bias_;  // transposed convolutions
  at::Tensor out_weight_, out_bias_;
};

TORCH_MODULE(UvDecoder);

}  // namespace layers::mgnet
