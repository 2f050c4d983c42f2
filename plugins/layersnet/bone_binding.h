// plugins/layersnet/bone_binding.h -- LayersNet's bone-bound integration
// base (`base: bones`): each garment vertex bound, once per sequence, to
// the skeleton bones nearest its rest position in the T-pose the rest
// shapes were made in (the two nearest bone segments, softly weighted), so
// the binding cannot jump to another limb during a rollout.
#pragma once

#include <ATen/ATen.h>

#include "layers/zoo/model.h"

namespace layers::layersnet {

// Softness of the two-bone blend: weights ~ exp(-distance / kBoneBlend) (m).
constexpr double kBoneBlend = 0.02;

struct BoneBinding {
  at::Tensor joint;   // [V,K] int64: the joint that moves each bound bone (its parent end)
  at::Tensor weight;  // [V,K] float, rows sum to 1 (K = 2, or 1 with a single bone)
};

// All garments' vertices in SequenceStatic order, on the device of the rest
// shapes. Throws InputError naming the sequence when it has no T-pose
// joints or parents, or fewer than one bone.
BoneBinding bind_to_bones(const zoo::SequenceStatic& s);

}  // namespace layers::layersnet
