// layers/zoo/losses.h -- the training losses shared by every model
// (the paper's loss terms; docs/training.md "Training step"). Each returns a
// differentiable scalar tensor on the inputs' device and in their floating
// type; nearest neighbours are found with the k-d tree of layers::geometry
// on detached CPU copies and the indices moved back to the inputs' device,
// so gradients flow through the positions only (never through the choice
// of neighbour); a surface that needs no gradient (the body) takes its
// vertex normals from layers::geometry on that CPU copy. Inputs are one frame: vertices [V,3] (floating point),
// faces [F,3] (any integer type); a wrong shape or type is a layers::Error
// naming the loss and the argument. Non-finite positions give a non-finite
// loss (the trainer's divergence check sees it); a non-finite surface
// (body or inner garment) is a layers::Error.
#pragma once

#include <ATen/ATen.h>

namespace layers::zoo {

// Mean over vertices of the squared distance |pred - truth|^2, [V,3] each.
at::Tensor position_mse(const at::Tensor& pred, const at::Tensor& truth);

// Mean over faces of |n_pred - n_truth|^2 for unit face normals. A
// degenerate (zero-area) face has normal 0.
//   pred   [V,3] predicted vertices
//   truth  [V,3] ground-truth vertices
//   faces  [F,3] int64 triangles shared by both meshes
at::Tensor normal_loss(const at::Tensor& pred, const at::Tensor& truth, const at::Tensor& faces);

// The paper's normal loss (its Eq. 13 and public code): mean over vertices
// of |n_pred - n_truth|^2 for unit area-weighted vertex normals
// (vertex_normals below); a vertex of no face, or only of degenerate
// faces, has normal 0. Arguments as normal_loss.
at::Tensor vertex_normal_loss(const at::Tensor& pred, const at::Tensor& truth, const at::Tensor& faces);

// Body collision (the paper's collision term; the nearest-vertex test of
// docs/metrics.md with a margin): for each garment vertex x with nearest
// body vertex h and body vertex normal n (vertex_normals below), d =
// (x - h).n; the loss is the mean of (eps - d)^2 over the vertices with
// d < eps, and 0 (with a zero gradient) when there are none or the body is
// empty. eps (metres, e.g. 0.005) must be finite.
//   garment     [V,3] predicted garment vertices
//   body        [Vb,3] body vertices at the predicted frame
//   body_faces  [Fb,3] int64 body triangles
at::Tensor body_collision_loss(const at::Tensor& garment, const at::Tensor& body, const at::Tensor& body_faces,
                               double eps);

// Layer collision: the same term for outer-garment vertices against the
// inner garment surface (inner vertices and faces; with several inner
// garments, concatenated). Gradients reach both layers (through h and n).
//   outer        [Vo,3] outer-garment vertices
//   inner        [Vi,3] inner-garment vertices
//   inner_faces  [Fi,3] int64 inner triangles
at::Tensor layer_collision_loss(const at::Tensor& outer, const at::Tensor& inner, const at::Tensor& inner_faces,
                                double eps);

// Area-weighted vertex normals of a mesh (unit length, [V,3]); a vertex of
// no face, or only of degenerate faces, gets 0. Differentiable; matches
// layers::geometry::vertex_normals.
at::Tensor vertex_normals(const at::Tensor& vertices, const at::Tensor& faces);

}  // namespace layers::zoo
