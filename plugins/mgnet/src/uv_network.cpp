// MGNet's UV-image encoder and decoder (see uv_network.h).
#include "layers/mgnet/uv_network.h"

#include <cmath>
#include <string>

namespace layers::mgnet {
namespace {

// Scale of the decoder's last layer at initialisation.
constexpr double kOutputInitScale = 0.01;

// A parameter of `shape`, uniform in +-sqrt(6 / fan_in) times `gain`.
at::Tensor he_uniform(torch::nn::Module& m, const std::string& name, at::IntArrayRef shape, double fan_in,
                      double gain = 1.0) {
  const double bound = gain * std::sqrt(6.0 / fan_in);
  return m.register_parameter(name, at::empty(shape, at::kFloat).uniform_(-bound, bound));
}

at::Tensor zero_bias(torch::nn::Module& m, const std::string& name, std::int64_t size) {
  return m.register_parameter(name, at::zeros({size}, at::kFloat));
}

}  // namespace

UvEncoderImpl::UvEncoderImpl(const UvEncoderOptions& options) {
  const std::vector<std::int64_t>& channels = options.channels();
  const std::int64_t in_channels = options.in_channels(), resolution = options.resolution(), latent = options.latent();
  std::int64_t in = in_channels, side = resolution;
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const std::string id = std::to_string(i);
    weight_.push_back(he_uniform(*this, "conv" + id + "_weight", {channels[i], in, 3, 3}, double(in * 9)));
    bias_.push_back(zero_bias(*this, "conv" + id + "_bias", channels[i]));
    in = channels[i];
    side /= 2;
  }
  const std::int64_t flat = in * side * side;
  head_weight_ = he_uniform(*this, "head_weight", {latent, flat}, double(flat), 1.0 / std::sqrt(2.0));
  head_bias_ = zero_bias(*this, "head_bias", latent);
}

at::Tensor UvEncoderImpl::forward(const at::Tensor& images) const {
  at::Tensor x = images;
  for (std::size_t i = 0; i < weight_.size(); ++i) x = at::silu(at::conv2d(x, weight_[i], bias_[i], 2, 1));
  return at::linear(x.flatten(1), head_weight_, head_bias_);
}

UvDecoderImpl::UvDecoderImpl(const UvDecoderOptions& options)
    : coarse_(options.resolution() >> options.channels().size()) {
  const std::vector<std::int64_t>& channels = options.channels();
  const std::int64_t code_size = options.code_size(), out_channels = options.out_channels();
  const std::int64_t last = channels.back(), flat = last * coarse_ * coarse_;
  head_weight_ = he_uniform(*this, "head_weight", {flat, code_size}, double(code_size));
  head_bias_ = zero_bias(*this, "head_bias", flat);
  // Stage i maps channels[i] to channels[i-1] (channels[0] for the last).
  for (std::size_t k = channels.size(); k-- > 0;) {
    const std::int64_t in = channels[k], out = channels[k == 0 ? 0 : k - 1];
    const std::string id = std::to_string(channels.size() - 1 - k);
    // A 4x4 stride-2 transposed convolution: each output pixel sees in x 2 x 2 inputs.
    weight_.push_back(he_uniform(*this, "deconv" + id + "_weight", {in, out, 4, 4}, double(in * 4)));
    bias_.push_back(zero_bias(*this, "deconv" + id + "_bias", out));
  }
  out_weight_ = he_uniform(*this, "out_weight", {out_channels, channels.front(), 3, 3}, double(channels.front() * 9),
                           kOutputInitScale);
  out_bias_ = zero_bias(*this, "out_bias", out_channels);
}

at::Tensor UvDecoderImpl::forward(const at::Tensor& code) const {
  at::Tensor x = at::silu(at::linear(code, head_weight_, head_bias_));
  x = x.reshape({code.size(0), -1, coarse_, coarse_});
  for (std::size_t i = 0; i < weight_.size(); ++i) x = at::silu(at::conv_transpose2d(x, weight_[i], bias_[i], 2, 1));
  return at::conv2d(x, out_weight_, out_bias_, 1, 1);
}

}  // namespace layers::mgnet
