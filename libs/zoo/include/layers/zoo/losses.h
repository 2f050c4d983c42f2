// layers/zoo/losses.h -- the training losses shared by every model
// (DESIGN.md section 4, PAPER_NOTES.md "Losses"). Each returns a
// differentiable scalar tensor on the inputs' device; nearest neighbours
// are found on detached copies (k-d tree), so gradients flow through the
// predicted positions only.
#pragma once

#include <ATen/ATen.h>

namespace layers::zoo {

// Mean over vertices of the squared distance |pred - truth|^2, [V,3] each.
at::Tensor position_mse(const at::Tensor& pred, const at::Tensor& truth);

// Mean over faces of |n_pred - n_truth|^2 for unit face normals; faces [F,3].
at::Tensor normal_loss(const at::Tensor& pred, const at::Tensor& truth, const at::Tensor& faces);

// Body collision (PAPER_NOTES.md): for each garment vertex x with nearest
// body vertex h and body vertex normal n, d = (x - h).n; the loss is the
// mean of (eps - d)^2 over vertices with d < eps (0 when none).
// body: [Vb,3] body vertices at the predicted frame, body_faces [Fb,3].
at::Tensor body_collision_loss(const at::Tensor& garment, const at::Tensor& body,
                               const at::Tensor& body_faces, double eps);

// Layer collision: the same term for outer-garment vertices against the
// inner garment surface (inner vertices and faces; with several inner
// garments, concatenated). Gradients reach both layers.
at::Tensor layer_collision_loss(const at::Tensor& outer, const at::Tensor& inner,
                                const at::Tensor& inner_faces, double eps);

// Area-weighted vertex normals of a mesh (unit length, [V,3]).
at::Tensor vertex_normals(const at::Tensor& vertices, const at::Tensor& faces);

}  // namespace layers::zoo
