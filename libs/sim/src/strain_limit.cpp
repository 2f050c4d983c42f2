// Strain limiting over the cloth's edges (see strain_limit.h).
#include "strain_limit.h"

namespace layers::sim::detail {

// Share of a correction a held vertex takes, relative to its mass weight.
constexpr double kHeldWeight = 0.2;

void limit_strain(const Cloth& cloth, Cloth::State& s, double max_strain, int sweeps,
                  const std::vector<std::uint8_t>* held) {
  const geometry::Edges& edges = cloth.edges();
  const Eigen::VectorXd& rest = cloth.rest_lengths();
  for (int sweep = 0; sweep < sweeps; ++sweep) {
    bool changed = false;
    for (Eigen::Index e = 0; e < edges.rows(); ++e) {
      const int a = edges(e, 0), b = edges(e, 1);
      double wa = s.inv_mass[a], wb = s.inv_mass[b];
      if (held && (*held)[a] != (*held)[b]) {
        if ((*held)[a]) wa *= kHeldWeight;
        else wb *= kHeldWeight;
      }
      if (wa + wb == 0.0) continue;
      const Vec3 d = s.x[b] - s.x[a];
      const double len = d.norm(), limit = (1.0 + max_strain) * rest[e];
      if (len <= limit) continue;
      const Vec3 correction = ((len - limit) / (len * (wa + wb))) * d;
      s.x[a] += wa * correction;
      s.x[b] -= wb * correction;
      changed = true;
    }
    if (!changed) break;
  }
}

}  // namespace layers::sim::detail
