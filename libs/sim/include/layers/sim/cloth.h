// layers/sim/cloth.h -- one garment as the solver sees it.
//
// A Cloth is built from its rest mesh (metres; faces wound so that normals
// point away from the body, i.e. outwards) and a Material. It owns:
//  - per-vertex mass: areal density x one third of the rest area of the
//    vertex's faces, so total mass does not depend on the mesh resolution;
//  - membrane elements: one per triangle, the map from its three positions
//    to the deformation gradient along the fabric's material axes (warp u,
//    weft v), for the stretch (tension/compression) and shear energies;
//  - bending elements: one per interior edge, the isometric (cotangent)
//    curvature stencil of its two triangles (flat rest state: cut fabric);
//  - the contact topology, edges with rest lengths (for the stretch
//    measure), the two-ring of each vertex (excluded from self-contact);
//  - its state: positions, velocities, pinned vertices.
// The material axes come from the UVs when given (the direction in which u
// grows), else from `grain` projected onto each rest triangle.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "layers/geometry/mesh.h"
#include "layers/sim/contact_topology.h"
#include "layers/sim/material.h"

namespace layers::sim {

using Vec3 = Eigen::Vector3d;
using Vec3s = std::vector<Vec3>;
using UVs = Eigen::Matrix<float, Eigen::Dynamic, 2, Eigen::RowMajor>;

struct ClothOptions {
  ClothOptions() = default;
  ClothOptions(std::string name_, int layer_, bool self_contact_ = false)
      : name(std::move(name_)), layer(layer_), self_contact(self_contact_) {}

  std::string name = "cloth";
  // Stacking order: a cloth is kept outside every cloth of a lower layer
  // (two-way contact); cloths of equal layer do not collide.
  int layer = 0;
  // Self-contact within this garment (skirts, hoods); also needs
  // SolverConfig::self_contact.
  bool self_contact = false;
  // Vertices held where they are (infinite mass).
  std::vector<int> pinned;
  // Optional UV layout (per face corner: uv_faces indexes uv rows); +u is
  // the warp direction. Empty: the grain direction below is used.
  UVs uv;
  geometry::Faces uv_faces;
  Vec3 grain{0.0, 1.0, 0.0};
};

// f_u = sum_k wu[k] x[v[k]] and f_v = sum_k wv[k] x[v[k]] are the
// deformed material axes (unit length at rest).
struct MembraneElement {
  std::array<int, 3> v;
  std::array<double, 3> wu, wv;
  double area;  // rest area, m^2
};

// Curvature vector c = sum_j k[j] x[v[j]] of the hinge (v0, v1) with
// opposite corners v2, v3 (cotangent weights of the rest triangles, so c
// vanishes on any flat configuration); bending energy 0.5 * B * weight *
// |c|^2, which converges to 0.5 * B * integral(kappa^2) dA under refinement
// (tests: a sheet wrapped on a cylinder).
struct BendingElement {
  std::array<int, 4> v;
  std::array<double, 4> k;
  double weight;  // 1 / (A0 + A1), 1/m^2
};

class Cloth {
 public:
  // What the solver integrates (double precision).
  struct State {
    Vec3s x;                       // positions
    Vec3s v;                       // velocities
    Vec3s x_start;                 // positions at the start of the current substep
    std::vector<double> inv_mass;  // 0 for pinned vertices
  };

  // Throws layers::InputError (naming options.name) for invalid faces,
  // non-finite or degenerate rest geometry, bad UVs or pinned indices.
  Cloth(const geometry::TriMesh& rest, const Material& material, ClothOptions options = {});

  const std::string& name() const { return options_.name; }
  int layer() const { return options_.layer; }
  bool self_contact() const { return options_.self_contact; }
  const Material& material() const { return material_; }

  int num_vertices() const { return static_cast<int>(state_.x.size()); }
  int num_faces() const { return static_cast<int>(faces_.rows()); }
  const geometry::Faces& faces() const { return faces_; }
  const geometry::Points& rest_positions() const { return rest_; }
  const Eigen::VectorXd& masses() const { return mass_; }
  double total_mass() const { return mass_.sum(); }
  bool pinned(int vertex) const { return state_.inv_mass[vertex] == 0.0; }

  // Current state as float rows, and setters (teleport: no motion is
  // implied). Throw InputError on a row-count mismatch or non-finite value.
  geometry::Points positions() const;
  geometry::Points velocities() const;
  geometry::TriMesh mesh() const { return {positions(), faces_}; }
  void set_positions(const geometry::Points& positions);
  void set_velocities(const geometry::Points& velocities);
  void pin(int vertex);

  const State& state() const { return state_; }
  const std::vector<MembraneElement>& membrane() const { return membrane_; }
  const std::vector<BendingElement>& bending() const { return bending_; }
  const ContactTopology& topology() const { return topology_; }
  const geometry::Edges& edges() const { return edges_; }
  const Eigen::VectorXd& rest_lengths() const { return rest_lengths_; }
  // Sorted vertices within two edges of v (v excluded); empty unless
  // self_contact() is on.
  const int* two_ring_begin(int v) const { return two_ring_.data() + two_ring_offsets_[v]; }
  const int* two_ring_end(int v) const { return two_ring_.data() + two_ring_offsets_[v + 1]; }
  bool in_two_ring(int v, int other) const;
  // Changes whenever something the solver precomputes from the cloth
  // changes (construction, assignment, pin()); unique across cloths.
  long revision() const { return revision_; }

 private:
  friend class Solver;

  void build_membrane();
  void build_bending();
  void build_two_ring();

  ClothOptions options_;
  Material material_;
  geometry::Points rest_;
  geometry::Faces faces_;
  Eigen::VectorXd mass_;
  State state_;
  std::vector<MembraneElement> membrane_;
  std::vector<BendingElement> bending_;
  ContactTopology topology_;
  geometry::Edges edges_;
  Eigen::VectorXd rest_lengths_;
  std::vector<int> two_ring_offsets_, two_ring_;
  long revision_ = 0;
};

}  // namespace layers::sim
