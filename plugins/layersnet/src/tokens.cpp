// Abstract-token inputs (see tokens.h).
#include "tokens.h"

namespace layers::layersnet {

at::Tensor scale_attributes(const at::Tensor& raw) {
  const at::TensorOptions o = raw.options().dtype(at::kFloat);
  const at::Tensor lo = at::tensor(at::ArrayRef<double>(kAttributeLow, kAttributes), o);
  const at::Tensor hi = at::tensor(at::ArrayRef<double>(kAttributeHigh, kAttributes), o);
  return (raw.to(at::kFloat) - lo) / (hi - lo);
}

bool wind_present(const zoo::StepInput& in) { return (in.wind_strength > 0).any().item<bool>(); }

at::Tensor wind_features(const zoo::StepInput& in, const zoo::Normalization& norm, const StepFrames& frames) {
  const at::Tensor& root = frames.root();
  const at::Tensor vel = frames.vectors_to_local(2, root.narrow(0, 1, 2) - root.narrow(0, 0, 2));  // [2,3]: t, t+1
  const at::Tensor acc = vel[1] - vel[0];
  return at::cat({norm.garment_velocity.scale(vel).reshape({-1}), norm.garment_acceleration.scale(acc),
                  frames.wind_to_local(in.wind_rotation).reshape({-1}), in.wind_strength.to(at::kFloat) / 400.0})
      .unsqueeze(0);
}

}  // namespace layers::layersnet
