// DeePSD's pose embedding input (see pose_features.h).
#include "pose_features.h"

#include <vector>

#include "layers/zoo/rotations.h"

namespace layers::deepsd {
namespace {

constexpr double kMaxWindStrength = 400.0;  // LAYERS-H5 wind/strength range

// Rotations [J,3,3] relative to the root's: R_r^T R_j.
at::Tensor relative_to_root(const at::Tensor& rotations, std::int64_t root) {
  return at::matmul(rotations[root].transpose(0, 1).unsqueeze(0), rotations);
}

}  // namespace

std::int64_t pose_feature_size(std::int64_t joints, bool wind) { return 6 * joints + 3 + (wind ? 4 : 0); }

at::Tensor pose_features(const at::Tensor& tpose, const at::Tensor& frame, std::int64_t root, bool wind,
                         const at::Tensor& wind_rotation, const at::Tensor& wind_strength) {
  const at::Tensor rf = frame.slice(2, 0, 3), rt = tpose.slice(2, 0, 3);
  const at::Tensor relative = at::matmul(relative_to_root(rf, root), relative_to_root(rt, root).transpose(1, 2));
  const at::Tensor to_rest = rf[root].transpose(0, 1);
  const at::Tensor down = at::tensor({0.0f, -1.0f, 0.0f}, frame.options());
  std::vector<at::Tensor> parts{relative.slice(2, 0, 2).reshape({-1}), at::matmul(to_rest, down)};
  if (wind) {
    const at::Tensor q = wind_rotation.to(frame.scalar_type());
    parts.push_back(at::matmul(to_rest, zoo::rotate_z(q)));
    parts.push_back((wind_strength.to(frame.scalar_type()) / kMaxWindStrength).reshape({1}));
  }
  return at::cat(parts);
}

}  // namespace layers::deepsd
