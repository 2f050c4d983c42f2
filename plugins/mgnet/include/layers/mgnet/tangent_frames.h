// layers/mgnet/tangent_frames.h -- per-vertex tangent frames of a garment
// mesh: normal + UV-aligned tangent + bitangent, and displacements moved
// between world and frame coordinates.
//
// The tangent of a face is dP/du, the direction in which the surface point
// moves when u grows and v stays put: T_f = (dv2 e1 - dv1 e2) / det with
// position edges e1, e2 and UV edges (du1, dv1), (du2, dv2), det = du1 dv2 -
// du2 dv1. A vertex sums T_f |det| over its faces (UV-area weighted; faces
// with det = 0 add nothing), and the frame is t = that sum made orthogonal
// to the area-weighted vertex normal n and unit length, b = n x t. The UV
// coefficients are fixed per face (derived once); only positions change, so
// the frame of the current positions follows the cloth. Fallbacks keep the
// frame orthonormal: a vertex without area gets n = +y, and where the UV
// tangent vanishes (or is parallel to n) t is the world x axis (z where
// |n.x| >= 0.9) made orthogonal to n.
#pragma once

#include <cstdint>
#include <vector>

#include <ATen/ATen.h>

namespace layers::mgnet {

struct TangentBasis {
  std::int64_t vertices = 0;
  at::Tensor faces;  // [F,3] int64
  at::Tensor coeff;  // [F,2] float: T_f |det| = coeff0 e1 + coeff1 e2
};

// A mesh's tangent basis, on the device of `faces`.
//   faces     [F,3] int64 vertex triangles
//   uv_faces  [F,3] int64 UV triangles
//   uv        [U,2] UV coordinates
TangentBasis tangent_basis(const at::Tensor& faces, const at::Tensor& uv_faces, const at::Tensor& uv,
                           std::int64_t vertices);

// Meshes side by side (vertex indices offset).
TangentBasis concatenate(const std::vector<TangentBasis>& parts);

// Frames at `positions` [V,3]: [V,3,3] with rows t, b, n (orthonormal,
// right-handed). Differentiable in the positions.
at::Tensor vertex_frames(const TangentBasis& basis, const at::Tensor& positions);

// World vector d [V,3] -> its components along (t, b, n) [V,3].
at::Tensor to_frame(const at::Tensor& frames, const at::Tensor& d);
// Components along (t, b, n) [V,3] -> world vector [V,3].
at::Tensor from_frame(const at::Tensor& frames, const at::Tensor& local);

}  // namespace layers::mgnet
