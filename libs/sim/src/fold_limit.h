// fold_limit.h (internal) -- a cap on how sharply the cloth may fold
// between two neighbouring triangles, applied after the elastic solve like
// the strain cap. A hinge (the edge v0-v1 with wings v2, v3) folded by more
// than `max_fold` (the angle between its two face normals; 0 = flat) has
// its wings pushed apart across the hinge line, mass-weighted, to the
// distance they would have at that angle with their present distances
// from the line. Isometric bending alone lets a 2.5 cm mesh crumple into
// folds of 150-180 degrees, finer than the mesh can carry, where the
// vertex normals stop describing the surface (docs/sim.md, "A cap on
// folds"). Hinges whose rest shape is already folded further keep their
// rest angle as their limit.
#pragma once

#include <vector>

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

class FoldLimiter {
 public:
  // Runs at most `sweeps` Gauss-Seidel sweeps over the hinges, stopping
  // after the first that moves nothing. `max_fold` in radians, in (0, pi).
  // Returns how many sweeps it ran (as StrainLimiter::apply); converged()
  // says whether the last one moved nothing.
  int apply(const Cloth& cloth, Cloth::State& state, double max_fold, int sweeps);
  bool converged() const { return converged_; }

 private:
  void build(const Cloth& cloth, double max_fold);

  long revision_ = -1;
  double max_fold_ = -1;
  bool converged_ = true;
  std::vector<double> cos_limit_;  // per bending element: cos of its largest allowed fold
};

}  // namespace layers::sim::detail
