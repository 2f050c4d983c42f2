// layers/sim/config.h -- typed settings of the cloth solver and of the
// per-sequence validation (cfg::read<SolverConfig>(node, "sim") fills them
// from YAML; every field has a default that the tests and docs/sim.md use).
#pragma once

#include <vector>

#include "layers/core/config.h"

namespace layers::sim {

// Thresholds a simulated sequence must stay under to be written
// (docs/metrics.md "Generator validation measures"; rates are fractions,
// not percent).
struct ValidationConfig {
  double max_h_penetration = 0.005;  // mean over frames of the H-penetration rate
  double max_l_penetration = 0.005;  // mean over frames of the L-penetration rate
  double max_stretch = 0.10;         // max over frames and edges of |l|/l0 - 1
  double l_reach = 0.03;             // only outer vertices this close to the inner layer can be behind it (m)
  double max_h_crossing = 1.0;       // largest share, in any frame, of garment vertices on faces through the body
  double max_l_crossing = 1.0;       // largest share, in any frame, of outer vertices on faces through the inner layer
  int max_cloth_crossings = 0;       // most crossing face pairs between garments (all pairs, and self) in any frame
  double pinch_distance = 0.018;     // m: two body parts closer than this pinch the cloth between them
  double max_h_crossing_clear =
      1.0;  // largest share, in any frame, of garment vertices crossing the body outside pinch zones

  template <class V>
  void visit(V& v) {
    v("max_h_penetration", max_h_penetration,
      cfg::opt().range(0, 1).help("mean share of garment vertices behind the body"));
    v("max_l_penetration", max_l_penetration,
      cfg::opt().range(0, 1).help("mean share of outer vertices behind the inner layer"));
    v("max_stretch", max_stretch, cfg::opt().min(0).help("largest allowed |l|/l0 - 1 of any edge"));
    v("l_reach", l_reach,
      cfg::opt().range(0.001, 10).help(
          "L-penetration: outer vertices farther than this from the inner layer are not tested (m)"));
    v("max_h_crossing", max_h_crossing,
      cfg::opt().range(0, 1).help(
          "largest share, in any frame, of garment vertices on faces passing through the body"));
    v("max_l_crossing", max_l_crossing,
      cfg::opt().range(0, 1).help(
          "largest share, in any frame, of outer vertices on faces passing through an inner garment"));
    v("pinch_distance", pinch_distance,
      cfg::opt().range(0, 0.2).help("pinch zones: body vertices closer than this (m) to a body vertex that is not "
                                    "their neighbour along the mesh (twice a two-layer cloth stack: 2 x (5 + 4) mm)"));
    v("max_h_crossing_clear", max_h_crossing_clear,
      cfg::opt().range(0, 1).help("largest share, in any frame, of garment vertices on faces passing through the body "
                                  "outside pinch zones (below 1, the generator measures pinch zones in every frame)"));
    v("max_cloth_crossings", max_cloth_crossings,
      cfg::opt().min(0).help("most crossing face pairs, in any frame, between two garments or within a garment with "
                             "self-contact (the collision pass keeps them at 0)"));
  }
};

struct SolverConfig {
  double fps = 30;                                  // frames per second; one step() is one frame
  int substeps = 10;                                // substeps per frame
  int iterations = 2;                               // local/global iterations per substep
  std::vector<double> gravity = {0.0, -9.81, 0.0};  // m/s^2
  double air_damping = 0.5;                         // 1/s: velocities decay as exp(-air_damping t)
  double max_speed = 30;                            // m/s cap on vertex speed (0: none); a guard against blow-ups
  double body_thickness = 0.005;                    // m kept between garments and the body surface
  double layer_thickness = 0.004;                   // m kept between an inner and an outer garment
  double layer_edge_thickness = 0.006;              // m kept between inner and outer edges (0: no edge-edge contact)
  double body_edge_thickness = 0.002;               // m kept between garment and body edges (0: off)
  int body_edge_every = 1;                          // the body edge-edge pass on every n-th substep (1: all)
  double self_thickness = 0.004;                    // m kept between two parts of one garment
  double max_strain = 0.08;       // strain limiting: edges are capped at (1 + max_strain) x rest (0: off)
  int strain_sweeps = 1000;       // most Gauss-Seidel sweeps of the cap after the contacts (stops when none moves)
  double max_fold = 0;            // degrees between neighbouring faces' normals a hinge may fold to (0: off)
  double support_stiffness = 1;   // body-contact support weight / the vertex's own stiffness (docs/sim.md)
  bool self_contact = true;       // master switch; each cloth also opts in (ClothOptions)
  double wind_pressure = 0.004;   // Pa per unit of Blender wind strength (docs/sim.md)
  bool collision_pass = false;    // the continuous-collision safety pass at the end of every substep (docs/sim.md)
  double collision_gap = 0.0005;  // m: the pass keeps every pair of features at least about this far apart
  int collision_rounds = 16;      // rounds of corrections before the fail-safe puts vertices back
  ValidationConfig validation;

  template <class V>
  void visit(V& v) {
    v("fps", fps, cfg::opt().range(1, 1000).help("frames per second"));
    v("substeps", substeps, cfg::opt().range(1, 1000).help("solver substeps per frame"));
    v("iterations", iterations, cfg::opt().range(1, 100).help("projective dynamics iterations per substep"));
    v("gravity", gravity, cfg::opt().help("gravity vector (m/s^2), three numbers"));
    v("air_damping", air_damping, cfg::opt().range(0, 1000).help("velocity decay rate (1/s)"));
    v("max_speed", max_speed, cfg::opt().min(0).help("vertex speed cap in m/s (0: none)"));
    v("body_thickness", body_thickness, cfg::opt().range(0, 0.1).help("garment-body distance (m)"));
    v("layer_thickness", layer_thickness, cfg::opt().range(0, 0.1).help("inner-outer garment distance (m)"));
    v("layer_edge_thickness", layer_edge_thickness,
      cfg::opt().range(0, 0.1).help("inner-outer edge-edge distance (m; 0: vertex-triangle contact only)"));
    v("body_edge_thickness", body_edge_thickness,
      cfg::opt().range(0, 0.1).help("garment-body edge-edge distance (m; 0: vertex-face body contact only)"));
    v("body_edge_every", body_edge_every,
      cfg::opt().range(1, 1000).help("run the garment-body edge-edge pass on every n-th substep of a frame, from "
                                     "the first (1: every substep; with the collision pass it only repairs "
                                     "crossings the pass did not prevent)"));
    v("self_thickness", self_thickness, cfg::opt().range(0, 0.1).help("distance within one garment (m)"));
    v("max_strain", max_strain, cfg::opt().range(0, 10).help("edge strain cap after the elastic solve (0: off)"));
    v("strain_sweeps", strain_sweeps,
      cfg::opt().range(1, 100000).help(
          "most sweeps of the strain cap after the contacts (it stops early once no edge is over)"));
    v("max_fold", max_fold,
      cfg::opt().range(0, 179).help(
          "fold cap: the most degrees between two neighbouring faces' normals after the elastic solve (0: off)"));
    v("support_stiffness", support_stiffness,
      cfg::opt().range(0, 100).help("weight of body-contact supports in the elastic solve, relative to each vertex's "
                                    "stiffness (0: projection only)"));
    v("self_contact", self_contact, cfg::opt().help("allow self-contact for cloths that ask for it"));
    v("wind_pressure", wind_pressure, cfg::opt().min(0).help("pressure (Pa) per unit of wind strength"));
    v("collision_pass", collision_pass,
      cfg::opt().help("continuous-collision safety pass at the end of every substep: no cloth passes through "
                      "another cloth during a substep (docs/sim.md)"));
    v("collision_gap", collision_gap,
      cfg::opt().range(1e-6, 0.01).help("least distance the collision pass keeps between features (m)"));
    v("collision_rounds", collision_rounds,
      cfg::opt().range(0, 100).help("rounds of collision-pass corrections before its fail-safe"));
    v("validation", validation);
  }
};

// Throws layers::InputError naming `what` if the config is inconsistent
// beyond the per-field ranges (gravity must have three finite numbers).
void check(const SolverConfig& config, const std::string& what = "sim");

}  // namespace layers::sim
