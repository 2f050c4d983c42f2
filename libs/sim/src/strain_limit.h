// strain_limit.h (internal) -- a safety net after the elastic solve:
// edges stretched beyond (1 + max_strain) times their rest length are
// shortened back to it (mass-weighted, Gauss-Seidel over the edges in a
// fixed order), as in Provot's strain limiting. Where the elastic solve has
// converged it does nothing; where a contact conflict or a tangle would
// over-stretch the cloth it caps the stretch.
#pragma once

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

void limit_strain(const Cloth& cloth, Cloth::State& state, double max_strain, int sweeps);

}  // namespace layers::sim::detail
