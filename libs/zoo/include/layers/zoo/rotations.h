// layers/zoo/rotations.h -- quaternion helpers the model plugins share
// (w,x,y,z order, as StepInput's root_rot and wind_rotation): rotation
// matrices, the image of +z, the heading (yaw about +y) of a rotation,
// products and conjugates. Quaternions are [...,4]: any leading
// dimensions, broadcast where two meet.
#pragma once

#include <ATen/ATen.h>

namespace layers::zoo {

// Rotation matrices [...,3,3] of quaternions [...,4] (normalised here, so
// any non-zero length will do).
at::Tensor rotation_matrices(const at::Tensor& quaternions);

// +z rotated by quaternions [...,4] (normalised here): [...,3], the last
// column of rotation_matrices.
at::Tensor rotate_z(const at::Tensor& quaternions);

// The heading of each rotation [...,4]: the rotation about +y ([...,4],
// (cos a/2, 0, sin a/2, 0)) that turns +z towards the horizontal part of
// the rotation's image of +z. A rotation that points +z straight up or
// down has heading 0.
at::Tensor heading_quaternions(const at::Tensor& quaternions);

// Hamilton products a b (shapes broadcast) and conjugates (inverse
// rotations).
at::Tensor quaternion_multiply(const at::Tensor& a, const at::Tensor& b);
at::Tensor quaternion_conjugate(const at::Tensor& q);

}  // namespace layers::zoo
