// The attribute -> material map: monotone in every attribute, the paper's
// ranges land in plausible physical ranges, bad values are rejected; the
// solver config reads and writes through cfg.
#include <gtest/gtest.h>

#include <cstdio>
#include <functional>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/sim/config.h"
#include "layers/sim/material.h"

namespace layers::sim {
namespace {

struct Case {
  const char* name;
  double GarmentAttributes::*attribute;
  double Material::*parameter;
  double lo, hi;  // the paper's range
};

const Case kCases[] = {
    {"mass", &GarmentAttributes::mass, &Material::density, 0.2, 0.8},
    {"tension", &GarmentAttributes::tension, &Material::tension_modulus, 15, 100},
    {"compression", &GarmentAttributes::compression, &Material::compression_modulus, 15, 100},
    {"shear", &GarmentAttributes::shear, &Material::shear_modulus, 15, 100},
    {"bending", &GarmentAttributes::bending, &Material::bending_rigidity, 15, 200},
    {"friction", &GarmentAttributes::friction, &Material::friction, 40, 80},
    {"self_friction", &GarmentAttributes::self_friction, &Material::self_friction, 40, 80},
};

TEST(Material, MappingIsStrictlyMonotoneInEachAttribute) {
  for (const Case& c : kCases) {
    double previous = -1;
    for (int i = 0; i <= 20; ++i) {
      GarmentAttributes a;
      a.*c.attribute = c.lo + (c.hi - c.lo) * i / 20.0;
      const Material m = to_material(a);
      EXPECT_GT(m.*c.parameter, previous) << c.name << " at step " << i;
      previous = m.*c.parameter;
      // The other parameters do not move.
      for (const Case& other : kCases) {
        if (other.parameter == c.parameter) continue;
        if (other.parameter == &Material::tension_modulus && c.parameter == &Material::compression_modulus) continue;
        EXPECT_EQ(m.*other.parameter, to_material(GarmentAttributes{}).*other.parameter)
            << c.name << " moved " << other.name;
      }
    }
  }
}

TEST(Material, PaperRangesArePhysicallyPlausible) {
  std::printf("[sim] attribute -> material over the paper's ranges:\n");
  for (const Case& c : kCases) {
    GarmentAttributes lo, hi;
    lo.*c.attribute = c.lo;
    hi.*c.attribute = c.hi;
    std::printf("[sim]   %-13s %6g..%-6g -> %.4g..%.4g\n", c.name, c.lo, c.hi, to_material(lo).*c.parameter,
                to_material(hi).*c.parameter);
  }
  GarmentAttributes light, heavy;
  light.mass = 0.2;
  heavy.mass = 0.8;
  EXPECT_NEAR(to_material(light).density, 0.1, 1e-12);  // kg/m^2: thin shirting
  EXPECT_NEAR(to_material(heavy).density, 0.4, 1e-12);  // kg/m^2: heavy denim / wool
  GarmentAttributes grippy;
  grippy.friction = 80;
  EXPECT_NEAR(to_material(grippy).friction, 0.8, 1e-12);
}

TEST(Material, RejectsNegativeOrNonPositiveValues) {
  GarmentAttributes a;
  a.mass = 0;
  EXPECT_THROW(to_material(a, {}, "jacket"), InputError);
  a = GarmentAttributes{};
  a.bending = -1;
  try {
    to_material(a, {}, "jacket");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("jacket"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("bending"), std::string::npos) << e.what();
  }
}

TEST(SolverConfig, ReadsWritesAndChecks) {
  const cfg::Node node =
      cfg::parse("substeps: 12\nbody_thickness: 0.004\nvalidation:\n  max_stretch: 0.2\n", "sim.yaml");
  const SolverConfig c = cfg::read<SolverConfig>(node, "sim");
  EXPECT_EQ(c.substeps, 12);
  EXPECT_DOUBLE_EQ(c.body_thickness, 0.004);
  EXPECT_DOUBLE_EQ(c.validation.max_stretch, 0.2);
  EXPECT_EQ(cfg::read<SolverConfig>(cfg::to_node(c), "sim").substeps, 12);
  EXPECT_THROW(cfg::read<SolverConfig>(cfg::parse("substep: 3\n", "sim.yaml"), "sim"), InputError);
  EXPECT_THROW(cfg::read<SolverConfig>(cfg::parse("substeps: 0\n", "sim.yaml"), "sim"), InputError);
  SolverConfig bad;
  bad.gravity = {0, -9.81};
  EXPECT_THROW(check(bad), InputError);
  const GarmentAttributes a = cfg::read<GarmentAttributes>(cfg::parse("mass: 0.3\nfriction: 45\n", "g.yaml"));
  EXPECT_DOUBLE_EQ(a.mass, 0.3);
  EXPECT_THROW(cfg::read<GarmentAttributes>(cfg::parse("friction: 95\n", "g.yaml")), InputError);
}

}  // namespace
}  // namespace layers::sim
