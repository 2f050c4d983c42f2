// The attribute -> material map (see material.h and docs/sim.md).
#include "layers/sim/material.h"

#include <cmath>
#include <string>

#include "layers/core/error.h"

namespace layers::sim {

namespace {

void require(bool ok, const std::string& what, const char* field, const char* expected, double got) {
  if (!ok) throw InputError(what, field, expected, std::to_string(got));
}

}  // namespace

Material to_material(const GarmentAttributes& a, const MaterialMapping& m, const std::string& what) {
  require(std::isfinite(a.mass) && a.mass > 0, what, "mass", "a positive number", a.mass);
  require(std::isfinite(a.tension) && a.tension >= 0, what, "tension", "a number >= 0", a.tension);
  require(std::isfinite(a.compression) && a.compression >= 0, what, "compression", "a number >= 0", a.compression);
  require(std::isfinite(a.shear) && a.shear >= 0, what, "shear", "a number >= 0", a.shear);
  require(std::isfinite(a.bending) && a.bending >= 0, what, "bending", "a number >= 0", a.bending);
  require(std::isfinite(a.friction) && a.friction >= 0, what, "friction", "a number >= 0", a.friction);
  require(std::isfinite(a.self_friction) && a.self_friction >= 0, what, "self_friction", "a number >= 0",
          a.self_friction);
  Material out;
  out.density = m.density_per_mass * a.mass;
  out.tension_modulus = m.modulus_per_stiffness * a.tension;
  out.compression_modulus = m.compression_per_stiffness * a.compression;
  out.shear_modulus = m.shear_per_stiffness * a.shear;
  out.bending_rigidity = m.rigidity_per_bending * a.bending;
  out.friction = m.friction_per_unit * a.friction;
  out.self_friction = m.friction_per_unit * a.self_friction;
  return out;
}

}  // namespace layers::sim
