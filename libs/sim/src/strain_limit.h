// strain_limit.h (internal) -- a safety net after the elastic solve:
// edges stretched beyond (1 + max_strain) times their rest length are
// shortened back below it (mass-weighted, Gauss-Seidel over the edges in a
// fixed order, over-relaxed), as in Provot's strain limiting. Where the elastic solve has
// converged it does nothing; where a contact conflict or a tangle would
// over-stretch the cloth it caps the stretch. Vertices flagged in `held`
// (touching the body or an inner layer) take a fifth of their share of a
// correction when the other end of the edge is free, so that the cap does
// not push contacts back through the surface they rest on.
//
// The first sweep visits every edge; each later sweep visits only the
// edges around the vertices the previous sweep moved (in index order), so
// a cap that needs many sweeps in one region (a neckline dragged by the
// skin) costs in proportion to that region, not to the whole garment.
#pragma once

#include <cstdint>
#include <vector>

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

class StrainLimiter {
 public:
  // Runs at most `sweeps` sweeps, stopping after the first that moves
  // nothing; an edge is corrected back to the cap only when it is more
  // than 0.5% of its length over it (8.54% for an 8% cap). Returns how
  // many sweeps it ran.
  int apply(const Cloth& cloth, Cloth::State& state, double max_strain, int sweeps,
            const std::vector<std::uint8_t>* held = nullptr);
  // Whether the last apply() ended because its last sweep moved nothing
  // (not because it ran out of sweeps while still correcting edges).
  bool converged() const { return active_.empty(); }

 private:
  void build(const Cloth& cloth);

  long revision_ = -1;
  std::vector<int> offsets_, incident_;  // edges around each vertex (CSR)
  std::vector<int> active_, next_;       // edges of this sweep and the next
  std::vector<std::uint8_t> queued_;     // per edge: in next_
};

}  // namespace layers::sim::detail
