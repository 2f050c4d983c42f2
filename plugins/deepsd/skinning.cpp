// Skinning from the T-pose and its inverse (see skinning.h).
#include "skinning.h"

namespace layers::deepsd {

at::Tensor tpose_to_frame(const at::Tensor& tpose, const at::Tensor& frame) {
  const at::Tensor rt = tpose.slice(2, 0, 3), pt = tpose.select(2, 3);
  const at::Tensor a = at::matmul(frame.slice(2, 0, 3), rt.transpose(1, 2));
  const at::Tensor b = frame.select(2, 3) - at::matmul(a, pt.unsqueeze(-1)).squeeze(-1);
  return at::cat({a, b.unsqueeze(-1)}, 2);
}

at::Tensor skin(const at::Tensor& points, const at::Tensor& weights, const at::Tensor& maps) {
  const std::int64_t v = points.size(0), j = maps.size(0);
  const at::Tensor blended = at::matmul(weights, maps.reshape({j, 12})).view({v, 3, 4});
  return at::matmul(blended.slice(2, 0, 3), points.unsqueeze(-1)).squeeze(-1) + blended.select(2, 3);
}

at::Tensor dense_weights(const at::Tensor& index, const at::Tensor& weight, std::int64_t joints) {
  const at::Tensor w = weight / weight.sum(1, /*keepdim=*/true);
  return at::zeros({index.size(0), joints}, weight.options()).scatter_add(1, index, w);
}

at::Tensor unskin(const at::Tensor& positions, const at::Tensor& skin_index, const at::Tensor& skin_weight,
                  const at::Tensor& maps) {
  const std::int64_t v = positions.size(0);
  const at::Tensor w = skin_weight / skin_weight.sum(1, /*keepdim=*/true);
  const at::Tensor per_vertex = maps.index_select(0, skin_index.reshape({-1})).view({v, 4, 3, 4});
  const at::Tensor blended = (per_vertex * w.view({v, 4, 1, 1})).sum(1);
  const at::Tensor rhs = (positions - blended.select(2, 3)).unsqueeze(-1);
  return at::linalg_solve(blended.slice(2, 0, 3), rhs).squeeze(-1);
}

std::int64_t root_joint(const at::Tensor& joint_parents) {
  if (!joint_parents.defined() || joint_parents.numel() == 0) return 0;
  const at::Tensor roots = at::nonzero(joint_parents.to(at::kCPU) < 0);
  return roots.size(0) > 0 ? roots[0][0].item<std::int64_t>() : 0;
}

}  // namespace layers::deepsd
