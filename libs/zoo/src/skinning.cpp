// Linear blend skinning on tensors (see skinning.h).
#include "layers/zoo/skinning.h"

#include "layers/geometry/nearest.h"

namespace layers::zoo {

// The 3x3 products are written as broadcasts and sums: with batched matmul
// (one tiny BLAS call per matrix) a skinned step took ~70 ms instead of
// ~1 ms on a busy 2-core CPU with 2 torch threads.
JointSteps joint_steps(const at::Tensor& joints, const at::Tensor& joints_next) {
  const at::Tensor r0 = joints.slice(2, 0, 3), p0 = joints.select(2, 3);
  const at::Tensor r1 = joints_next.slice(2, 0, 3), p1 = joints_next.select(2, 3);
  const at::Tensor m = (r1.unsqueeze(2) * r0.unsqueeze(1)).sum(-1);
  return {m, p1 - (m * p0.unsqueeze(1)).sum(-1)};
}

JointSteps blend_joint_steps(const JointSteps& steps, const at::Tensor& joint, const at::Tensor& weight,
                             at::ScalarType type) {
  const std::int64_t nv = joint.size(0), k = joint.size(1);
  const at::Tensor flat = joint.flatten();
  const at::Tensor w = weight.to(type);
  return {(w.view({nv, k, 1, 1}) * steps.m.to(type).index_select(0, flat).view({nv, k, 3, 3})).sum(1),
          (w.view({nv, k, 1}) * steps.c.to(type).index_select(0, flat).view({nv, k, 3})).sum(1)};
}

at::Tensor move_with_joints(const JointSteps& steps, const at::Tensor& points, const at::Tensor& joint,
                            const at::Tensor& weight) {
  const JointSteps blended = blend_joint_steps(steps, joint, weight, points.scalar_type());
  return (blended.m * points.unsqueeze(1)).sum(-1) + blended.c;
}

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

namespace {

// Each vertex's blended map [Vb,3,4] from the four-influence weights.
at::Tensor blended_maps(const at::Tensor& skin_index, const at::Tensor& skin_weight, const at::Tensor& maps) {
  const std::int64_t v = skin_index.size(0);
  const at::Tensor w = skin_weight / skin_weight.sum(1, /*keepdim=*/true);
  const at::Tensor per_vertex = maps.index_select(0, skin_index.reshape({-1})).view({v, 4, 3, 4});
  return (per_vertex * w.view({v, 4, 1, 1})).sum(1);
}

}  // namespace

at::Tensor unskin(const at::Tensor& positions, const at::Tensor& skin_index, const at::Tensor& skin_weight,
                  const at::Tensor& maps) {
  const at::Tensor blended = blended_maps(skin_index, skin_weight, maps);
  const at::Tensor rhs = (positions - blended.select(2, 3)).unsqueeze(-1);
  return at::linalg_solve(blended.slice(2, 0, 3), rhs).squeeze(-1);
}

double smallest_blend_determinant(const at::Tensor& skin_index, const at::Tensor& skin_weight, const at::Tensor& maps) {
  if (skin_index.size(0) == 0) return 1.0;
  return at::linalg_det(blended_maps(skin_index, skin_weight, maps).slice(2, 0, 3)).abs().min().item<double>();
}

std::int64_t root_joint(const at::Tensor& joint_parents) {
  if (!joint_parents.defined() || joint_parents.numel() == 0) return 0;
  const at::Tensor roots = at::nonzero(joint_parents.to(at::kCPU) < 0);
  return roots.size(0) > 0 ? roots[0][0].item<std::int64_t>() : 0;
}

namespace {

// A float32 CPU copy of [N,3] positions as geometry points.
geometry::Points cpu_points(const at::Tensor& x) {
  const at::Tensor c = x.detach().to(at::kCPU, at::kFloat).contiguous();
  return Eigen::Map<const geometry::Points>(c.data_ptr<float>(), c.size(0), 3);
}

}  // namespace

at::Tensor nearest_body_vertex(const at::Tensor& points, const at::Tensor& body) {
  const geometry::PointIndex tree(cpu_points(body));
  Eigen::VectorXi nearest = tree.nearest_all(cpu_points(points));
  return at::from_blob(nearest.data(), {nearest.size()}, at::kInt).to(points.device(), at::kLong);
}

SkinBinding skin_of_rows(const at::Tensor& rows, const at::Tensor& skin_index, const at::Tensor& skin_weight) {
  const at::Tensor r = rows.to(skin_index.device());
  const at::Tensor w = skin_weight.index_select(0, r);
  return {skin_index.index_select(0, r), w / w.sum(1, /*keepdim=*/true)};
}

SkinBinding bind_to_nearest_skin(const at::Tensor& points, const at::Tensor& body, const at::Tensor& skin_index,
                                 const at::Tensor& skin_weight) {
  return skin_of_rows(nearest_body_vertex(points, body), skin_index, skin_weight);
}

}  // namespace layers::zoo
