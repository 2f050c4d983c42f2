// layers/motion/clip_ops.h -- what the dataset generator does to a
// retargeted clip to get more than one motion out of it: mirror it left to
// right, and cut a window out of it that starts at rest.
#pragma once

#include <string>
#include <vector>

#include "layers/body/skeleton.h"

namespace layers::motion {

// Mirror across the sagittal plane (x = 0; the rig faces +z with +y up):
// joints named Left* and Right* (and L* and R*, as LHipJoint and RThumb) swap, every rotation is reflected (the
// quaternion (w, x, y, z) becomes (w, x, -y, -z)) and the root's x is
// negated. Exact for a left-right symmetric rest skeleton, which the
// body's is up to its rest joint positions.
class PoseMirror {
 public:
  explicit PoseMirror(const body::Skeleton& skeleton);
  body::Pose operator()(const body::Pose& pose) const;
  int partner(int joint) const { return partner_.at(static_cast<std::size_t>(joint)); }

 private:
  std::vector<int> partner_;
};

// Frames [start, start + frames) of `poses` as a new clip that starts at
// rest: for start > 0 the first `ease` frames replay the clip from `start`
// on with a speed rising smoothly from 0 to 1 (time warp t^2 - t^3/3, C2 at
// the join), so the window consumes ease/3 fewer clip frames than it has.
// The root is moved so the first frame stands above (0, 0). Throws
// layers::Error when the window does not fit.
std::vector<body::Pose> clip_window(const std::vector<body::Pose>& poses, int start, int frames, int ease = 15);

// Frames of a BVH clip at 30 fps (the length a window must fit in).
// `path` as in MotionSpec (a .bvh path or one in the asset folder's
// motions/); InputError when it is missing or malformed.
int bvh_clip_frames(const std::string& path, const std::string& asset_root = "");

}  // namespace layers::motion
