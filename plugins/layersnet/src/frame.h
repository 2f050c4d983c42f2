// plugins/layersnet/src/frame.h -- the moving frames LayersNet sees a step in:
// for each of t-1, t, t+1, origin at the body root and, with
// `heading_frame`, axes turned with the root's heading (yaw about +y, so
// gravity stays -y); without it, world axes (translation only). Positions
// and velocities go in, the predicted positions come back out, and the
// wind's rotation is expressed relative to the frame of t+1.
#pragma once

#include <cstdint>

#include <ATen/ATen.h>

#include "layers/zoo/model.h"

namespace layers::layersnet {

class StepFrames {
 public:
  // Frames of `in` (root [3,3], root_rot [3,4]); heading = false ignores root_rot.
  StepFrames(const zoo::StepInput& in, bool heading);

  // Points [N,3] in frame k (0: t-1, 1: t, 2: t+1): R_k^T (p - root_k).
  at::Tensor to_local(std::int64_t k, const at::Tensor& points) const;
  // Directions [N,3] in frame k: R_k^T v.
  at::Tensor vectors_to_local(std::int64_t k, const at::Tensor& vectors) const;
  // Points of frame k back to the world: R_k l + root_k.
  at::Tensor to_world(std::int64_t k, const at::Tensor& local) const;
  // Wind rotations [N,4] (w,x,y,z) relative to frame t+1: h_2^-1 q.
  at::Tensor wind_to_local(const at::Tensor& wind_rotation) const;
  // The root at t-1, t, t+1 [3,3] (float).
  const at::Tensor& root() const { return root_; }

 private:
  at::Tensor root_;     // [3,3] float
  at::Tensor axes_;     // [3,3,3] R_k (undefined: world axes)
  at::Tensor heading_;  // [3,4] heading quaternions (undefined: world axes)
};

}  // namespace layers::layersnet
