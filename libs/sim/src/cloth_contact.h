// cloth_contact.h (internal) -- contacts between cloth surfaces: an inner
// and an outer garment (two-way, both directions of vertex-triangle), and
// one garment with itself. Each keeps a reusable spatial hash.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <vector>

#include "layers/geometry/mesh.h"
#include "layers/sim/cloth.h"
#include "spatial_hash.h"

namespace layers::sim::detail {

// Edge-edge proximity of two surfaces, an inner one (a garment, or the
// body) and an outer garment: an outer edge and an inner edge closer than
// `thickness` are pushed apart along the line between their closest points
// as it was at the start of the substep, so that two edges cannot pass
// through each other between the vertex tests (vertex-triangle contact
// alone lets a fold of one layer, or a ridge of the body, slip through the
// other's edge first). Where the inner side gives an outward direction per
// edge (the body), an outer edge found on its inside is pushed outwards
// instead (it has crossed: put it back). Mass-weighted by the points'
// barycentric weights; no friction; vertices with zero inverse mass stay.
struct EdgeContact {
  // One surface's edges and positions for a substep.
  struct Side {
    const geometry::Edges* edges = nullptr;
    const Vec3s* start = nullptr;                   // positions at the start of the substep
    Vec3s* x = nullptr;                             // positions now, moved by the contact ...
    const Vec3s* fixed = nullptr;                   // ... or now, for a side that never moves (x null)
    const std::vector<double>* inv_mass = nullptr;  // per vertex (ignored for a fixed side)
    Vec3s* push = nullptr;                          // the pushes are added here (moving sides)
    const Vec3s* outward = nullptr;                 // per edge, unit (optional; inner side only)
    const Vec3s& now() const { return x != nullptr ? *x : *fixed; }
  };
  // Pushes apart every listed pair (an outer edge, an inner edge; from the
  // shared candidate list, contact_candidates.h) closer than thickness, in
  // the list's order. Returns the largest move it gave an outer vertex.
  static double collide(const Side& inner, const Side& outer, double thickness,
                        const std::vector<std::array<int, 2>>& pairs);
};

// Two-way contact between an inner and an outer garment.
//  - projection: keeps the outer garment's vertices `thickness` outside the
//    inner garment's surface (its normal side) and the inner garment's
//    vertices `thickness` inside the outer one, with mass-weighted
//    corrections and friction mu. Precisely: each vertex keeps the side it
//    was on at the start of the substep (outside, resp. inside, when it was
//    exactly on the surface), so layers that start apart never cross and a
//    hem that legitimately tucks under is not pushed through a sheet
//    (without the collision pass, a vertex found less than a thickness on
//    the wrong side is taken back to the preferred side); an open boundary (a hem, a cuff) is a thin rod to keep
//    `thickness` from. Layers that start crossed are not untangled: the warm-up must begin from separated garments.
//    Then edge-edge proximity (EdgeContact, collide_edges()).
//  - support: an outer vertex touching an inner garment at the start of a
//    frame is kept, in the outer garment's elastic solve, outside the plane
//    of the inner face it touches (a one-sided attachment like the body
//    supports, see body_collider.h); the reaction goes to the inner
//    garment's vertices as a force in their next iteration, so the inner
//    garment carries the outer one's weight.
class LayerContact {
 public:
  // On when the collision pass runs (it guarantees the side a vertex
  // starts a substep on): the side is then never overridden.
  void set_guarded(bool on) { guarded_ = on; }
  // Per vertex of an outer cloth.
  struct Memory {
    std::vector<std::uint8_t> touching;  // within 1.5 x thickness of an inner garment after the last substep
    std::vector<int> inner;              // index of that inner cloth (-1: none)
    std::vector<int> face;               // its face
    std::vector<std::array<double, 3>> bary;
    std::vector<std::uint8_t> wanted;   // supported this frame
    std::vector<std::uint8_t> claimed;  // its attachment was aimed at an inner garment this iteration
    Vec3s target;                       // support target of the current iteration
    // Nearest vertex of another cloth's surface found last time (warm
    // start of the search), and which cloth that was.
    std::vector<int> near_vertex, near_cloth;
    void resize(int n);
    void forget_touching();
  };

  // Projection of one (inner, outer) pair, named by their cloth indices;
  // records touching in `outer_memory`. Inner vertices flagged in `backed`
  // (held by the body) are not moved: the body behind them takes the push.
  // Normal pushes are added to `inner_push` and `outer_push`.
  void collide(int inner_index, const Cloth& inner, Cloth::State& inner_state, Memory& inner_memory, int outer_index,
               const Cloth& outer, Cloth::State& outer_state, Memory& outer_memory,
               const std::vector<std::uint8_t>& backed, double thickness, double mu, Vec3s& inner_push,
               Vec3s& outer_push);
  // Then the pair's edge-edge proximity at `edge_thickness` over `pairs`
  // (an outer edge, an inner edge), the inner vertices held as collide()
  // held them.
  void collide_edges(const Cloth& inner, Cloth::State& inner_state, const Cloth& outer, Cloth::State& outer_state,
                     double edge_thickness, const std::vector<std::array<int, 2>>& pairs, Vec3s& inner_push,
                     Vec3s& outer_push);

  // After the body has had its say: the outer garment's vertices alone are
  // pushed back outside the inner one (the inner garment does not move), so
  // a body push on the inner garment cannot leave the layers crossed.
  void settle_outer(int inner_index, const Cloth& inner, Cloth::State& inner_state, const Cloth& outer,
                    Cloth::State& outer_state, Memory& outer_memory, double thickness, double mu, Vec3s& outer_push);

  // Frame start: supports for the outer vertices that were touching.
  static void make_supports(const Cloth::State& outer, Memory& memory);
  // Before an elastic iteration of the outer cloth: for the vertices with
  // an attachment weight not yet claimed (by the body), targets on the
  // inner faces' planes (inner positions as they are now); adds weight x
  // target to `rhs`.
  static void aim_supports(const Cloth::State& outer, Memory& memory, const std::vector<double>& weights,
                           const std::vector<Cloth>& cloths, double thickness, Vec3s& rhs,
                           std::vector<std::uint8_t>& claimed);
  // After it: adds the reactions (minus the support forces, spread by
  // barycentric weight) to `reactions` of the inner cloths.
  static void record_supports(const Cloth::State& outer, const Memory& memory, const std::vector<double>& weights,
                              const std::vector<Cloth>& cloths, std::vector<Vec3s>& reactions);

 private:
  SpatialHash grid_;
  bool guarded_ = false;
  std::vector<double> inner_inv_mass_;
  Vec3s no_push_;
};

// Keeps each vertex `thickness` away from the garment's own faces that do
// not touch its two-ring, on the side it was on at the start of the
// substep (so sheets that meet cannot pass through each other), and
// `thickness` away from its own open boundaries.
class SelfContact {
 public:
  // Normal pushes are added to `push`.
  void collide(const Cloth& cloth, Cloth::State& state, double thickness, double mu, Vec3s& push);

 private:
  SpatialHash grid_;
};

}  // namespace layers::sim::detail
