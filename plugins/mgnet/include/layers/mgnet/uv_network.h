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
#include <vector>

#include <ATen/ATen.h>
#include <torch/nn/module.h>

namespace layers::mgnet {

class UvEncoder : public torch::nn::Module {
 public:
  // Images of `in_channels` x resolution x resolution; channels per stage
  // (resolution divisible by 2^stages, checked by read_params()).
  UvEncoder(std::int64_t in_channels, const std::vector<std::int64_t>& channels, std::int64_t resolution,
            std::int64_t latent);
  // [G,in,R,R] -> [G,latent]
  at::Tensor forward(const at::Tensor& images) const;

 private:
  std::vector<at::Tensor> weight_, bias_;
  at::Tensor head_weight_, head_bias_;
};

class UvDecoder : public torch::nn::Module {
 public:
  // A code of `code_size` -> `out_channels` x resolution x resolution,
  // mirroring an encoder with these stage channels.
  UvDecoder(std::int64_t code_size, const std::vector<std::int64_t>& channels, std::int64_t resolution,
            std::int64_t out_channels);
  // [G,code] -> [G,out,R,R]
  at::Tensor forward(const at::Tensor& code) const;

 private:
  std::int64_t coarse_ = 0;  // side of the coarsest grid
  at::Tensor head_weight_, head_bias_;
  std::vector<at::Tensor> weight_, bias_;  // transposed convolutions
  at::Tensor out_weight_, out_bias_;
};

}  // namespace layers::mgnet
