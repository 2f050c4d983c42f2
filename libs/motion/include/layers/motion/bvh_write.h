// layers/motion/bvh_write.h -- a clip written as BVH (what read_bvh reads
// back): the hierarchy depth first with each joint's offset, the root with
// position and rotation channels, every other joint with rotations only,
// each rotation as "Zrotation Yrotation Xrotation" (Rz * Ry * Rx), lengths
// in centimetres. Used to ship clips converted from ASF/AMC; a joint other
// than the root keeps its offset (a clip whose other joints translate in
// some frame is refused: BVH here carries no such channels).
#pragma once

#include <set>
#include <string>

#include "layers/motion/bvh.h"

namespace layers::motion {

// The clip without the joints named in `drop` (and all below them); a
// joint left without children gets an End Site at its first dropped
// child's offset.
BvhClip without_joints(const BvhClip& clip, const std::set<std::string>& drop);

// Writes `clip` to `path` (atomically; InputError when a non-root joint
// translates off its offset).
void write_bvh(const BvhClip& clip, const std::string& path);

}  // namespace layers::motion
