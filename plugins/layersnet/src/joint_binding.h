// plugins/layersnet/src/joint_binding.h -- what binds garment vertices to the
// skeleton for LayersNet's followed-motion bases: `base: bones` (the
// skeleton bones nearest each vertex's rest position in the T-pose the
// rest shapes were made in, the two nearest segments softly weighted) and
// `base: skin` (the skinning weights of the body vertex nearest each rest
// position, the body brought back to that T-pose). Either binding is made
// once per sequence, so it cannot jump to another limb during a rollout.
#pragma once

#include <ATen/ATen.h>

#include "layers/zoo/model.h"

namespace layers::layersnet {

// Softness of the two-bone blend: weights ~ exp(-distance / kBoneBlend) (m).
constexpr double kBoneBlend = 0.02;

// Joints moving each vertex (zoo::move_with_joints' joint and weight).
struct JointBinding {
  at::Tensor joint;   // [V,K] int64
  at::Tensor weight;  // [V,K] float, rows sum to 1
};

// All garments' vertices in SequenceStatic order, on the device of the rest
// shapes; each bound to the joint that moves its nearest bones (their
// parent end; K = 2, or 1 with a single bone). Throws InputError naming the
// sequence when it has no T-pose joints or parents, or fewer than one bone.
JointBinding bind_to_bones(const zoo::SequenceStatic& s);

// Throws InputError naming the sequence and field when it lacks what
// bind_to_skin needs (skin_index, skin_weight, tpose_joints); called when
// the sequence is prepared, before any step.
void check_skin_data(const zoo::SequenceStatic& s);

// All garments' vertices (SequenceStatic order, on body_t's device), each
// bound to the four skinning joints and weights of the body vertex nearest
// its rest position, with the body `body_t` [Vb,3] at a frame whose joint
// transforms are `joints_t` [J,3,4] brought back to the T-pose by
// inverting each vertex's blended joint map (exact where one joint moves a
// vertex, close where rotations blend). Throws InputError for a joint index
// outside the skeleton, a non-positive weight sum or a singular blend.
JointBinding bind_to_skin(const zoo::SequenceStatic& s, const at::Tensor& body_t, const at::Tensor& joints_t);

}  // namespace layers::layersnet
