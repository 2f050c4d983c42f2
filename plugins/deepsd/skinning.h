// plugins/deepsd/skinning.h -- linear blend skinning from the T-pose the
// garments were made in (SequenceStatic::tpose_joints) to a frame
// (StepInput::joints_next), and its inverse for body vertices.
//
// Joint transforms are [J,3,4] rows [R|p] (LAYERS-H5 body/joints). Joint j
// maps a T-pose point x to frame f with G_j(f) G_j(T)^-1:
//   x -> A_j x + b_j,  A_j = R_j(f) R_j(T)^T,  b_j = p_j(f) - A_j p_j(T),
// and a vertex with weights w_vj moves by sum_j w_vj (A_j x + b_j).
#pragma once

#include <ATen/ATen.h>

#include <cstdint>

namespace layers::deepsd {

// The per-joint maps [J,3,4] = [A_j | b_j] from the T-pose to `frame`.
at::Tensor tpose_to_frame(const at::Tensor& tpose, const at::Tensor& frame);

// Skins points [V,3] with dense weights [V,J] through maps [J,3,4].
at::Tensor skin(const at::Tensor& points, const at::Tensor& weights, const at::Tensor& maps);

// Dense [V,J] weights from the four-influence form (index [V,4], weight
// [V,4]), renormalised to sum 1 per row.
at::Tensor dense_weights(const at::Tensor& index, const at::Tensor& weight, std::int64_t joints);

// The T-pose positions of body vertices given at a frame (positions
// [Vb,3], their skinning index/weight [Vb,4], maps T-pose -> frame):
// solves sum_k w_k (A_k x + b_k) = y for x, per vertex.
at::Tensor unskin(const at::Tensor& positions, const at::Tensor& skin_index, const at::Tensor& skin_weight,
                  const at::Tensor& maps);

// The root joint: the first joint without a parent (0 when parents are
// not given).
std::int64_t root_joint(const at::Tensor& joint_parents);

}  // namespace layers::deepsd
