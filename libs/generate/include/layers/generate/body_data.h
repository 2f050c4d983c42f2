// layers/generate/body_data.h -- the body part of a LAYERS-H5 sequence
// from a generated body (layers::scene -> layers::data).
#pragma once

#include <Eigen/Geometry>
#include <cstdint>
#include <string>

#include "layers/data/sequence.h"
#include "layers/motion/body_config.h"

namespace layers::generate {

// Fills body/faces, positions, root, root_rot, joints, joint names and
// parents and skinning, and the sequence's shape parameters and frame
// count, from frames [first, first + count) of `generated` (count < 0: to
// the end). body/tpose_joints is the body's T-pose moved by
// `tpose_placement`: the rigid motion the garments' rest shapes (fitted
// around the T-pose body) were moved by.
void fill_body(data::SequenceData& seq, const motion::GeneratedBody& generated, int first = 0, int count = -1,
               const Eigen::Isometry3d& tpose_placement = Eigen::Isometry3d::Identity());

// A sequence with the body only: no garments, and no wind (strength 0,
// identity rotation) for every frame.
data::SequenceData body_only_sequence(const motion::GeneratedBody& generated, const std::string& id,
                                      std::uint64_t seed);

}  // namespace layers::generate
