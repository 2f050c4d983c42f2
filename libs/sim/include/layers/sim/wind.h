// layers/sim/wind.h -- the wind field: a direction and a Blender strength
// (0-400) that stay constant within a span of frames.
//
// Wind acts on each face as a pressure normal to it:
//   F_face = pressure_per_strength * strength * area * (n . w) n,
// which always points downwind (F . w = P A (n . w)^2 >= 0), is the same for
// either orientation of n (both sides of a thin sheet catch wind) and is zero
// for faces parallel to the wind. A third goes to each corner. The pressure
// constant (SolverConfig::wind_pressure) is calibrated in docs/sim.md.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "layers/sim/cloth.h"

namespace layers::sim {

struct Wind {
  Vec3 direction{0.0, 0.0, 1.0};  // unit vector the wind blows towards
  double strength = 0;            // Blender units, 0-400 in the paper

  // From a quaternion (w, x, y, z; normalised here) that rotates +z onto the
  // wind direction (the LAYERS-H5 / Blender convention).
  static Wind from_rotation(const Eigen::Vector4d& wxyz, double strength);
  // The shortest-arc quaternion (w, x, y, z) rotating +z onto direction.
  Eigen::Vector4d rotation() const;
  bool calm() const { return strength == 0.0; }
};

// A frame range [begin, end) with constant wind.
struct WindSpan {
  int begin = 0;
  int end = 0;
  Wind wind;
};

// Non-overlapping spans; frames outside every span are calm.
class WindSchedule {
 public:
  WindSchedule() = default;
  // Throws layers::InputError if spans overlap, are empty or reversed, or a
  // direction is not a unit vector (within 1e-3) or a strength is negative.
  explicit WindSchedule(std::vector<WindSpan> spans);
  Wind at(int frame) const;
  const std::vector<WindSpan>& spans() const { return spans_; }

 private:
  std::vector<WindSpan> spans_;  // sorted by begin
};

// Adds the wind force (N) on every vertex of the mesh `faces` at positions
// `x` to `forces` (same size as x), with pressure = pressure_per_strength *
// wind.strength Pa.
void add_wind_forces(const std::vector<std::array<int, 3>>& faces, const Vec3s& x, const Wind& wind,
                     double pressure_per_strength, Vec3s& forces);

}  // namespace layers::sim
