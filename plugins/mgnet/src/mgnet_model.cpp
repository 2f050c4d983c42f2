// The MGNet model: derive() builds the UV layout of a sequence's garments,
// predict() encodes the step's UV maps (state and dynamic encoders), decodes
// a displacement image, samples it at each vertex and adds it, in the
// vertex's current tangent frame, to a base prediction (following the
// body seeds, or root-relative constant velocity). All garments run as one
// batch of images through the same weights; the layer map tells inner from
// outer. See docs/mgnet.md.
#include <memory>

#include "layers/mgnet/input_maps.h"
#include "layers/mgnet/layout.h"
#include "layers/mgnet/params.h"
#include "layers/mgnet/uv_network.h"
#include "layers/zoo/model.h"
#include "layers/zoo/phase.h"
#include "spec.h"

namespace layers::mgnet {
namespace {

class MGNet : public zoo::Model {
 public:
  explicit MGNet(const Params& p) : Model(kMgnet.name), params_(p), base_(p.base) {
    state_encoder_ = register_module("state_encoder",
                                     UvEncoder(UvEncoderOptions(kStateChannels, p.channels, p.resolution, p.latent)));
    dynamic_encoder_ = register_module(
        "dynamic_encoder", UvEncoder(UvEncoderOptions(kDynamicChannels, p.channels, p.resolution, p.latent)));
    decoder_ = register_module("decoder", UvDecoder(UvDecoderOptions(2 * p.latent, p.channels, p.resolution, 3)));
  }

  cfg::Node config() const override { return cfg::to_node(params_); }

 protected:
  struct Layout : Derived {
    GarmentLayout value;
  };

  std::shared_ptr<const Derived> derive(const zoo::SequenceStatic& data) override {
    auto out = std::make_shared<Layout>();
    out->value = make_layout(data, params_.resolution);
    return out;
  }

  zoo::StepOutput predict(const zoo::StepInput& in) override {
    const GarmentLayout& layout = derived<Layout>().value;
    zoo::StepOutput out;
    if (layout.sizes.empty()) return out;
    const zoo::Normalization& norm = normalization();
    const zoo::Phase phase_maps("phase:uv_maps");
    const StepMaps maps = step_maps(layout, in, norm, base_);
    const zoo::Phase phase_network("phase:uv_network");
    const at::Tensor code = at::cat({state_encoder_->forward(maps.state), dynamic_encoder_->forward(maps.dynamic)}, 1);
    const at::Tensor decoded = decoder_->forward(code);
    const zoo::Phase phase_sample("phase:uv_sample");
    const at::Tensor local = sample(layout.splat, decoded);
    // The decoder speaks normalised accelerations; the frame mixes the
    // world axes, so one scale: the mean of the per-axis deviations.
    const at::Tensor displacement = from_frame(maps.frames, local) * norm.garment_acceleration.std.mean();
    out.garments = (maps.base + displacement).split_with_sizes(layout.sizes);
    return out;
  }

 private:
  Params params_;
  Base base_;
  UvEncoder state_encoder_{nullptr}, dynamic_encoder_{nullptr};
  UvDecoder decoder_{nullptr};
};

}  // namespace

std::shared_ptr<zoo::Model> make_mgnet(const cfg::Node& params) { return std::make_shared<MGNet>(read_params(params)); }

}  // namespace layers::mgnet
