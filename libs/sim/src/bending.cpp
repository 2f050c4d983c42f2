// Isometric bending for projective dynamics (see projective.h): the hinge
// curvature vector c = sum_j k_j x_j is linear in the positions and its
// target is zero, so the term is B * weight * k k^T in the system matrix.
#include "projective.h"

namespace layers::sim::detail {

void add_bending_matrix(const Cloth& cloth, Triplets& out) {
  const double rigidity = cloth.material().bending_rigidity;
  if (!(rigidity > 0)) return;
  for (const BendingElement& b : cloth.bending()) {
    const double w = rigidity * b.weight;
    for (int i = 0; i < 4; ++i)
      for (int j = 0; j < 4; ++j) out.emplace_back(b.v[i], b.v[j], w * b.k[i] * b.k[j]);
  }
}

}  // namespace layers::sim::detail
