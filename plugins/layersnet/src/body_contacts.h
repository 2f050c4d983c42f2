// plugins/layersnet/src/body_contacts.h -- which next-frame body vertices
// matter to LayersNet: up to K senders per patch (the closest body
// vertices within the radius of its centroid) and, per garment vertex, the
// nearest body vertex within the radius (for the decoder). Found with a
// k-d tree on detached CPU copies, built only over the body vertices inside
// the garment's bounding box grown by the radius, so body vertices far from
// the garment cost one comparison each and change nothing.
#pragma once

#include <cstdint>

#include <ATen/ATen.h>

namespace layers::layersnet {

struct BodyContacts {
  at::Tensor ids;            // [B] int64 body vertices used as tokens, in order of first use
  at::Tensor slot;           // [P,K] int64 rows of `ids` (0 where unused)
  at::Tensor slot_valid;     // [P,K] bool
  at::Tensor nearest;        // [V] int64 body vertex nearest each garment vertex (0 where none)
  at::Tensor nearest_valid;  // [V] bool: nearer than the radius
};

// Body senders of each patch and each vertex's nearest body vertex (any
// device, any floating type); results are int64/bool tensors on the CPU.
//   body_next  [Vb,3] body vertices at t+1
//   centroids  [P,3] patch centroids at t
//   vertices   [V,3] garment vertices at t
BodyContacts find_body_contacts(const at::Tensor& body_next, const at::Tensor& centroids, const at::Tensor& vertices,
                                double radius, std::int64_t max_senders);

}  // namespace layers::layersnet
