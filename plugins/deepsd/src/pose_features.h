// plugins/deepsd/src/pose_features.h -- the input of DeePSD's pose embedding
// at frame t+1, all in the body's rest frame so that it does not depend on
// where the body stands or faces:
//   - per joint j, the 6D rotation (first two columns) of A_j B_j^T with
//     A_j = R_r(f)^T R_j(f) and B_j = R_r(T)^T R_j(T) (r the root joint):
//     the joint's rotation away from the T-pose, relative to the root;
//     identity for every joint in the T-pose (6J values);
//   - the gravity direction R_r(f)^T (0,-1,0) (3 values: the body's tilt);
//   - with wind, the wind direction (the wind rotation applied to +z)
//     R_r(f)^T d and strength/400 (4 values), as the paper extended DeePSD.
#pragma once

#include <ATen/ATen.h>

#include <cstdint>

namespace layers::deepsd {

std::int64_t pose_feature_size(std::int64_t joints, bool wind);

// DeePSD's pose descriptor at frame f; root: the root joint.
//   tpose          [J,3,4] joint transforms of the T-pose
//   frame          [J,3,4] joint transforms at f
//   wind_rotation  [4] (w,x,y,z) at f, read when `wind`
//   wind_strength  [] or [1] 0..400 at f, read when `wind`
at::Tensor pose_features(const at::Tensor& tpose, const at::Tensor& frame, std::int64_t root, bool wind,
                         const at::Tensor& wind_rotation, const at::Tensor& wind_strength);

}  // namespace layers::deepsd
