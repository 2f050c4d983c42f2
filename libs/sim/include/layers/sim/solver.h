// layers/sim/solver.h -- the multi-garment cloth solver.
//
// Substepped projective dynamics with position-based contacts (docs/sim.md):
// each frame (1/fps s) is split into `substeps` substeps; each substep
// predicts positions from velocities, gravity, wind and air damping, runs
// `iterations` local/global projective-dynamics iterations for the membrane
// (stretch, shear) and bending energies (implicit Euler) -- in which the body
// and inner garments support what rests on them (attachments fixed per
// frame) -- caps edge strain, then projects the contacts: inner/outer
// layers (two-way), self-contact, the body (kinematic), and the outer layers
// once more against the inner ones, caps strain once more, and ends with
// the continuous-collision safety pass (collision_pass.h: no cloth passes
// through another, or through itself where it has self-contact, during the
// substep; velocities follow from the position change (cloth-cloth pushes
// and the pass's corrections add none). The body is a triangle mesh
// whose vertices move linearly from one frame's pose to the next across the
// substeps, so fast limbs advance only a fraction of a frame per substep.
// Everything runs on one thread in a fixed order: the same inputs give
// bit-identical outputs.
//
//   sim::Solver solver(config);
//   int inner = solver.add_cloth(sim::Cloth(rest_inner, material, sim::ClothOptions("tshirt", 0)));
//   int outer = solver.add_cloth(sim::Cloth(rest_outer, material2, sim::ClothOptions("jacket", 1)));
//   solver.set_body(body_mesh_frame0);
//   for (frame ...) solver.step(body_positions[frame + 1], schedule.at(frame));
//   geometry::Points p = solver.cloth(outer).positions();
#pragma once

#include <memory>
#include <vector>

#include "layers/geometry/mesh.h"
#include "layers/sim/cloth.h"
#include "layers/sim/config.h"
#include "layers/sim/wind.h"

namespace layers::sim {

// Wall-clock seconds spent per phase since the last reset_timings().
struct StepTimings {
  double predict = 0;        // forces, damping, prediction, velocity update
  double elastic = 0;        // supports and refactorisation, stretch/shear/bending iterations, first strain cap
  double layer_contact = 0;  // inner/outer garments
  double self_contact = 0;
  double body_contact = 0;         // including the per-substep body interpolation and grid
  double strain_cap = 0;           // the strain cap after the contacts
  long cap_sweeps = 0;             // sweeps it ran (all cloths and substeps)
  long cap_unfinished = 0;         // cap calls that used all strain_sweeps while still correcting edges
  double collision_pass = 0;       // the continuous-collision safety pass
  long pass_pairs = 0;             // colliding pairs it met (first round of each substep)
  long pass_zoned = 0;             // cloth vertices it moved rigidly with an impact zone (per zone round)
  long pass_reverted = 0;          // cloth vertices its fail-safe put back at the substep's start
  long pass_yielded = 0;           // body pairs the body swept through cloth that could not move
  long candidate_builds = 0;       // times the shared contact candidates were made (contact_candidates.h) ...
  long candidate_body_builds = 0;  // ... times only their body pairs were ...
  long candidate_refreshes = 0;    // ... and times they were refreshed locally
  long candidate_pairs = 0;        // pairs they held, summed over substeps
  double total = 0;
  long frames = 0;
};

class Solver {
 public:
  // Throws InputError if the config is invalid (see check()).
  explicit Solver(SolverConfig config = {});
  ~Solver();
  Solver(Solver&&) noexcept;
  Solver& operator=(Solver&&) noexcept;
  Solver(const Solver&) = delete;
  Solver& operator=(const Solver&) = delete;

  // Adds a garment; returns its index. Cloths are simulated together.
  int add_cloth(Cloth cloth);
  int num_cloths() const { return static_cast<int>(cloths_.size()); }
  Cloth& cloth(int index);
  const Cloth& cloth(int index) const;

  // The body collider: faces (wound outwards) and its current pose.
  // Replaces any previous body. InputError for invalid faces or positions.
  void set_body(const geometry::TriMesh& body);
  // Moves the body to a pose at once (no motion is implied, nothing is
  // pushed): e.g. to restart at another frame. Same vertex count.
  void set_body_positions(const geometry::Points& positions);
  bool has_body() const;
  const geometry::TriMesh& body() const { return body_; }

  // Advances one frame. The body moves linearly from its current pose to
  // `body_next` across the substeps and ends there. InputError if there is
  // no body or body_next has the wrong size or non-finite values.
  void step(const geometry::Points& body_next, const Wind& wind = {});
  // Advances one frame with the body (if any) standing still.
  void step(const Wind& wind = {});

  const SolverConfig& config() const { return config_; }
  // Replaces the settings between frames (e.g. more damping for a warm-up).
  void set_config(const SolverConfig& config);
  long frame() const { return frame_; }

  const StepTimings& timings() const { return timings_; }
  void reset_timings() { timings_ = {}; }

 private:
  struct Impl;
  void advance(const geometry::Points* body_next, const Wind& wind);
  // The phases of advance(), in the order it calls them (solver.cpp): once
  // per frame, then per substep.
  void prepare_frame(double h, bool body);
  double predict(double h, const Wind& unit_wind);
  void elastic_iterations(bool body);
  void cap_folds_and_strain();
  void project_layer_contacts();
  void project_self_contacts();
  void project_body_contacts(bool body, double body_edges, double h);
  void settle_outer_layers();
  void recap_strain(bool body);
  void update_velocities(double h);
  // The end of a substep: the collision pass and the strain cap after it.
  void collision_pass(bool body);
  template <class F>
  void for_each_layer_pair(F&& f);

  SolverConfig config_;
  std::vector<Cloth> cloths_;
  geometry::TriMesh body_;
  long frame_ = 0;
  StepTimings timings_;
  std::unique_ptr<Impl> impl_;
};

}  // namespace layers::sim
