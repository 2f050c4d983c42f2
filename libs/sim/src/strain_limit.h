// strain_limit.h (internal) -- a safety net after the elastic solve:
// edges stretched beyond (1 + max_strain) times their rest length are
// shortened back to it (mass-weighted, Gauss-Seidel over the edges in a
// fixed order), as in Provot's strain limiting. Where the elastic solve has
// converged it does nothing; where a contact conflict or a tangle would
// over-stretch the cloth it caps the stretch. Vertices flagged in `held`
// (touching the body or an inner layer) move only when both ends of an
// edge are held, so that the cap does not push contacts back through the
// surface they rest on.
#pragma once

#include <cstdint>
#include <vector>

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

void limit_strain(const Cloth& cloth, Cloth::State& state, double max_strain, int sweeps,
                  const std::vector<std::uint8_t>* held = nullptr);

}  // namespace layers::sim::detail
