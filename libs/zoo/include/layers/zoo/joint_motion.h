// layers/zoo/joint_motion.h -- how a skeleton's joints move points from
// one frame to the next (StepInput::joints convention, [J,3,4] = [R|p]):
// the per-joint affine maps, and points carried by a blend of joints.
// Shared by the skinned reference and LayersNet's bone-bound base.
#pragma once

#include <ATen/ATen.h>

namespace layers::zoo {

// Per joint j, x -> M_j x + c_j moves a point with joint j from t to t+1:
// M_j = R_j(t+1) R_j(t)^T, c_j = p_j(t+1) - M_j p_j(t). Returns
// {M [J,3,3], c [J,3]}.
struct JointSteps {
  at::Tensor m;
  at::Tensor c;
};
JointSteps joint_steps(const at::Tensor& joints, const at::Tensor& joints_next);

// Per point, the blend of its joints' maps: weight [V,K] times the maps of
// joint [V,K] (int64), summed: {M [V,3,3], c [V,3]}, in `type`.
JointSteps blend_joint_steps(const JointSteps& steps, const at::Tensor& joint, const at::Tensor& weight,
                             at::ScalarType type);

// Points [V,3] moved by the blend of their joints: joint [V,K] (int64) and
// weight [V,K] (summing to 1): sum_k w_k (M_jk x + c_jk), in the points'
// dtype.
at::Tensor move_with_joints(const JointSteps& steps, const at::Tensor& points, const at::Tensor& joint,
                            const at::Tensor& weight);

}  // namespace layers::zoo
