// layers/zoo/skinning.h -- linear blend skinning for models, on tensors:
// how joints move points between frames, from the T-pose the garments were
// made in to a frame and back, and binding points to the skinning weights
// of their nearest body vertex. One module for the `skinned` reference,
// DeePSD and LayersNet (the generator's own skinning, on Eigen, is in
// libs/body).
//
// Joint transforms are [J,3,4] rows [R|p] (LAYERS-H5 body/joints and
// tpose_joints; StepInput::joints). Joint j maps a T-pose point x to frame
// f with G_j(f) G_j(T)^-1:
//   x -> A_j x + b_j,  A_j = R_j(f) R_j(T)^T,  b_j = p_j(f) - A_j p_j(T),
// and from frame t to t+1 with M_j = R_j(t+1) R_j(t)^T,
// c_j = p_j(t+1) - M_j p_j(t). A vertex with weights w_vj moves by
// sum_j w_vj (A_j x + b_j).
#pragma once

#include <cstdint>

#include <ATen/ATen.h>

namespace layers::zoo {

// Per-joint affine maps x -> M_j x + c_j: {M [J,3,3], c [J,3]}.
struct JointSteps {
  at::Tensor m;
  at::Tensor c;
};

// The maps that move a point with each joint from t to t+1.
//   joints       [J,3,4] joint transforms at t
//   joints_next  [J,3,4] joint transforms at t+1
JointSteps joint_steps(const at::Tensor& joints, const at::Tensor& joints_next);

// Per point, the blend of its joints' maps, in `type`.
//   steps   per-joint maps {[J,3,3], [J,3]}
//   joint   [V,K] int64 joints of each point
//   weight  [V,K] their weights (summing to 1)
// Returns {M [V,3,3], c [V,3]}.
JointSteps blend_joint_steps(const JointSteps& steps, const at::Tensor& joint, const at::Tensor& weight,
                             at::ScalarType type);

// Points moved by the blend of their joints, sum_k w_k (M_jk x + c_jk), in
// the points' dtype.
//   points  [V,3]
//   joint   [V,K] int64
//   weight  [V,K] summing to 1
at::Tensor move_with_joints(const JointSteps& steps, const at::Tensor& points, const at::Tensor& joint,
                            const at::Tensor& weight);

// The per-joint maps [J,3,4] = [A_j | b_j] from the T-pose to a frame.
//   tpose  [J,3,4] joint transforms of the T-pose
//   frame  [J,3,4] joint transforms at the frame
at::Tensor tpose_to_frame(const at::Tensor& tpose, const at::Tensor& frame);

// Skins points with dense weights through per-joint maps.
//   points   [V,3] in the T-pose
//   weights  [V,J] dense, rows summing to 1
//   maps     [J,3,4] from tpose_to_frame
at::Tensor skin(const at::Tensor& points, const at::Tensor& weights, const at::Tensor& maps);

// Dense [V,J] weights from the four-influence form, rows renormalised to 1.
//   index   [V,4] joint indices
//   weight  [V,4]
at::Tensor dense_weights(const at::Tensor& index, const at::Tensor& weight, std::int64_t joints);

// The T-pose positions of body vertices given at a frame: solves
// sum_k w_k (A_k x + b_k) = y for x, per vertex (exact where one joint
// moves a vertex, close where rotations blend).
//   positions    [Vb,3] at the frame
//   skin_index   [Vb,4] joint indices
//   skin_weight  [Vb,4] weights (renormalised here)
//   maps         [J,3,4] T-pose -> frame (tpose_to_frame)
at::Tensor unskin(const at::Tensor& positions, const at::Tensor& skin_index, const at::Tensor& skin_weight,
                  const at::Tensor& maps);

// The smallest |det| of the blended linear parts that unskin inverts;
// callers refuse a sequence whose blends cannot be inverted.
//   skin_index   [Vb,4] joint indices
//   skin_weight  [Vb,4] weights
//   maps         [J,3,4] T-pose -> frame
double smallest_blend_determinant(const at::Tensor& skin_index, const at::Tensor& skin_weight, const at::Tensor& maps);

// The root joint: the first joint without a parent (0 when parents are
// not given).
std::int64_t root_joint(const at::Tensor& joint_parents);

// Each point's nearest body vertex (k-d tree on CPU), as int64 [V] on the
// points' device. Both must be finite.
//   points  [V,3]
//   body    [Vb,3]
at::Tensor nearest_body_vertex(const at::Tensor& points, const at::Tensor& body);

// Joints and weights binding points to the skinning of a body vertex each.
struct SkinBinding {
  at::Tensor joint;   // [V,4] int64
  at::Tensor weight;  // [V,4], rows sum to 1
};

// The skinning joints and weights of body vertices `rows` [V] (int64),
// weights renormalised per row. The caller checks that every selected
// weight sum is positive (SkinBinding::weight is finite then).
SkinBinding skin_of_rows(const at::Tensor& rows, const at::Tensor& skin_index, const at::Tensor& skin_weight);

// skin_of_rows of each point's nearest body vertex.
//   points       [V,3] where the points are, in the body's frame
//   body         [Vb,3] body vertices in that frame
//   skin_index   [Vb,4] int64 joint indices
//   skin_weight  [Vb,4]
SkinBinding bind_to_nearest_skin(const at::Tensor& points, const at::Tensor& body, const at::Tensor& skin_index,
                                 const at::Tensor& skin_weight);

}  // namespace layers::zoo
