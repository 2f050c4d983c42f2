// Cross-field checks of the solver settings (see config.h).
#include "layers/sim/config.h"

#include <cmath>
#include <string>

#include "layers/core/error.h"

namespace layers::sim {

void check(const SolverConfig& c, const std::string& what) {
  if (c.gravity.size() != 3) {
    throw InputError(what, "gravity", "three numbers (x, y, z)", std::to_string(c.gravity.size()) + " numbers");
  }
  for (double g : c.gravity) {
    if (!std::isfinite(g)) throw InputError(what, "gravity", "finite numbers", "a non-finite value");
  }
  const auto positive = [&](double value, const char* field) {
    if (!(value > 0) || !std::isfinite(value)) {
      throw InputError(what, field, "a positive number", std::to_string(value));
    }
  };
  positive(c.fps, "fps");
  if (c.substeps < 1) throw InputError(what, "substeps", "an integer >= 1", std::to_string(c.substeps));
  if (c.iterations < 1) throw InputError(what, "iterations", "an integer >= 1", std::to_string(c.iterations));
  const auto non_negative = [&](double value, const char* field) {
    if (!(value >= 0) || !std::isfinite(value)) {
      throw InputError(what, field, "a number >= 0", std::to_string(value));
    }
  };
  non_negative(c.air_damping, "air_damping");
  non_negative(c.max_speed, "max_speed");
  non_negative(c.body_thickness, "body_thickness");
  non_negative(c.layer_thickness, "layer_thickness");
  non_negative(c.self_thickness, "self_thickness");
  non_negative(c.wind_pressure, "wind_pressure");
  non_negative(c.support_stiffness, "support_stiffness");
  non_negative(c.max_strain, "max_strain");
}

}  // namespace layers::sim
