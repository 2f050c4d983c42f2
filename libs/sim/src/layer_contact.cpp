// Two-way contact between an inner and an outer garment (see
// cloth_contact.h).
#include <algorithm>
#include <cmath>
#include <limits>

#include "cloth_contact.h"
#include "contact_response.h"
#include "surface_query.h"

namespace layers::sim::detail {

namespace {

// Vertices of `points` against the surface of `surface` (indexed by grid).
// Each vertex keeps the side of the surface it was on at the start of the
// substep (`preferred`: +1 the normal side, -1 behind, when it was exactly
// on it); `memory` (of the points' cloth) holds the warm start of the
// nearest-vertex search, and with `record` touching vertices seen from the
// preferred side are recorded there (for supports).
void points_against_surface(Cloth::State& points, const std::vector<double>& point_inv_mass, const Cloth& surface,
                            Cloth::State& surface_state, const std::vector<double>& surface_inv_mass,
                            const SpatialHash& grid, double preferred, double thickness, double mu, int surface_index,
                            LayerContact::Memory& memory, bool record, bool guarded, Vec3s& point_push,
                            Vec3s& surface_push) {
  const double radius = grid.cell();
  const ContactTopology& topology = surface.topology();
  for (std::size_t i = 0; i < points.x.size(); ++i) {
    const Vec3 p = points.x[i];
    int nearest = -1;
    double best = radius * radius;
    if (memory.near_cloth[i] == surface_index) {
      const double d2 = (surface_state.x[memory.near_vertex[i]] - p).squaredNorm();
      if (d2 < best) {
        best = d2;
        nearest = memory.near_vertex[i];
      }
    }
    grid.visit(p, std::sqrt(best), [&](int j) {
      const double d2 = (surface_state.x[j] - p).squaredNorm();
      if (d2 < best) {
        best = d2;
        nearest = j;
      }
    });
    memory.near_vertex[i] = nearest;
    memory.near_cloth[i] = nearest < 0 ? -1 : surface_index;
    SurfaceHit hit;
    if (nearest < 0 || !closest_around(topology, surface_state.x, nearest, p, hit)) continue;
    const double before = side_offset(topology, surface_state.x_start, hit, points.x_start[i]);
    double side = before > 0 ? 1.0 : before < 0 ? -1.0 : preferred;
    // Without the collision pass, a vertex found less than a thickness on
    // the wrong side of the surface it faces (e.g. after the nearest face
    // switched to another sheet of a fold, or a shallow crossing in an
    // earlier substep) is taken back to the preferred side rather than kept
    // crossed. With the pass (`guarded`) nothing crosses, so the side at the
    // start of the substep is the true one and is kept.
    if (!guarded && side != preferred && hit.facing && -preferred * hit.offset < thickness) side = preferred;
    if (record && side == preferred && hit.facing && side * hit.offset < 1.5 * thickness) {
      memory.touching[i] = 1;
      memory.inner[i] = surface_index;
      memory.face[i] = hit.face;
      memory.bary[i] = hit.bary;
    }
    Vec3 normal;
    double depth;
    if (!cloth_push(hit, p, side, thickness, normal, depth)) continue;
    resolve_two_way(points.x, points.x_start, point_inv_mass, static_cast<int>(i), surface_state.x,
                    surface_state.x_start, surface_inv_mass, TriangleRef{topology.faces[hit.face], hit.bary}, normal,
                    depth, mu, point_push, surface_push);
  }
}

}  // namespace

void LayerContact::Memory::resize(int n) {
  touching.assign(n, 0);
  inner.assign(n, -1);
  face.assign(n, -1);
  bary.assign(n, {0, 0, 0});
  wanted.assign(n, 0);
  claimed.assign(n, 0);
  target.assign(n, Vec3::Zero());
  near_vertex.assign(n, -1);
  near_cloth.assign(n, -1);
}

void LayerContact::Memory::forget_touching() { std::fill(touching.begin(), touching.end(), 0); }

void LayerContact::collide(int inner_index, const Cloth& inner, Cloth::State& inner_state, Memory& inner_memory,
                           int outer_index, const Cloth& outer, Cloth::State& outer_state, Memory& outer_memory,
                           const std::vector<std::uint8_t>& backed, double thickness, double mu, Vec3s& inner_push,
                           Vec3s& outer_push) {
  inner_inv_mass_ = inner_state.inv_mass;
  for (std::size_t i = 0; i < backed.size(); ++i) {
    if (backed[i]) inner_inv_mass_[i] = 0.0;
  }
  grid_.build(inner_state.x, 1.5 * thickness + inner.topology().reach());
  points_against_surface(outer_state, outer_state.inv_mass, inner, inner_state, inner_inv_mass_, grid_, +1.0, thickness,
                         mu, inner_index, outer_memory, true, guarded_, outer_push, inner_push);
  grid_.build(outer_state.x, 1.5 * thickness + outer.topology().reach());
  points_against_surface(inner_state, inner_inv_mass_, outer, outer_state, outer_state.inv_mass, grid_, -1.0, thickness,
                         mu, outer_index, inner_memory, false, guarded_, inner_push, outer_push);
}

void LayerContact::collide_edges(const Cloth& inner, Cloth::State& inner_state, const Cloth& outer,
                                 Cloth::State& outer_state, double edge_thickness,
                                 const std::vector<std::array<int, 2>>& pairs, Vec3s& inner_push, Vec3s& outer_push) {
  if (edge_thickness <= 0 || pairs.empty()) return;
  const EdgeContact::Side in{&inner.edges(), &inner_state.x_start, &inner_state.x,
                             nullptr,        &inner_inv_mass_,     &inner_push};
  const EdgeContact::Side out{&outer.edges(), &outer_state.x_start,  &outer_state.x,
                              nullptr,        &outer_state.inv_mass, &outer_push};
  EdgeContact::collide(in, out, edge_thickness, pairs);
}

void LayerContact::settle_outer(int inner_index, const Cloth& inner, Cloth::State& inner_state, const Cloth& outer,
                                Cloth::State& outer_state, Memory& outer_memory, double thickness, double mu,
                                Vec3s& outer_push) {
  // Zero inverse masses: the inner garment does not move.
  inner_inv_mass_.assign(inner_state.x.size(), 0.0);
  no_push_.assign(inner_state.x.size(), Vec3::Zero());
  grid_.build(inner_state.x, 1.5 * thickness + inner.topology().reach());
  points_against_surface(outer_state, outer_state.inv_mass, inner, inner_state, inner_inv_mass_, grid_, +1.0, thickness,
                         mu, inner_index, outer_memory, false, guarded_, outer_push, no_push_);
}

void LayerContact::make_supports(const Cloth::State& outer, Memory& memory) {
  for (std::size_t i = 0; i < outer.x.size(); ++i) {
    memory.wanted[i] = memory.touching[i] && memory.inner[i] >= 0 && outer.inv_mass[i] != 0.0;
  }
}

namespace {

// Unit normal and a point of face `face` of `cloth` at its current positions.
bool face_plane(const Cloth& cloth, int face, Vec3& normal, Vec3& point) {
  const auto& f = cloth.topology().faces[face];
  const Vec3s& x = cloth.state().x;
  const Vec3 n = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
  const double len = n.norm();
  if (!(len > 0)) return false;
  normal = n / len;
  point = x[f[0]];
  return true;
}

}  // namespace

void LayerContact::aim_supports(const Cloth::State& outer, Memory& memory, const std::vector<double>& weights,
                                const std::vector<Cloth>& cloths, double thickness, Vec3s& rhs,
                                std::vector<std::uint8_t>& claimed) {
  for (std::size_t i = 0; i < outer.x.size(); ++i) {
    memory.claimed[i] = 0;
    if (weights[i] == 0.0 || claimed[i] || !memory.wanted[i]) continue;
    claimed[i] = memory.claimed[i] = 1;
    Vec3 n, q;
    if (!face_plane(cloths[memory.inner[i]], memory.face[i], n, q)) {
      memory.target[i] = outer.x[i];
    } else {
      // A support only makes small corrections: a vertex more than a
      // thickness behind a (possibly stale) plane is left to the projection.
      const double gap = thickness - (outer.x[i] - q).dot(n);
      memory.target[i] = outer.x[i] + (gap > 0 && gap < 2 * thickness ? gap : 0.0) * n;
    }
    rhs[i] += weights[i] * memory.target[i];
  }
}

void LayerContact::record_supports(const Cloth::State& outer, const Memory& memory, const std::vector<double>& weights,
                                   const std::vector<Cloth>& cloths, std::vector<Vec3s>& reactions) {
  for (std::size_t i = 0; i < outer.x.size(); ++i) {
    if (!memory.claimed[i]) continue;
    const Vec3 force = weights[i] * (memory.target[i] - outer.x[i]);
    const auto& f = cloths[memory.inner[i]].topology().faces[memory.face[i]];
    Vec3s& reaction = reactions[memory.inner[i]];
    for (int k = 0; k < 3; ++k) reaction[f[k]] -= memory.bary[i][k] * force;
  }
}

}  // namespace layers::sim::detail
