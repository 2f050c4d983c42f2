// Joint motion between frames (see joint_motion.h).
#include "layers/zoo/joint_motion.h"

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

}  // namespace layers::zoo
