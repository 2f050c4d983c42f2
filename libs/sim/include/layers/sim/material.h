// layers/sim/material.h -- garment attributes and the physical material.
//
// GarmentAttributes are the paper's per-garment numbers in Blender's units
// (mass 0.2-0.8, tension/compression/shear 15-100, bending 15-200, friction
// and self-friction 40-80). Material is what the solver uses: an areal
// density, 2D moduli per unit length, a bending rigidity and Coulomb
// coefficients, all defined per area or per length so that the same garment
// behaves the same at any mesh resolution. MaterialMapping holds the
// constants of the (linear, monotone) map from one to the other; the table
// and its reasoning are in docs/sim.md.
#pragma once

#include "layers/core/config.h"

namespace layers::sim {

// The paper's attributes (Blender semantics, docs/sim.md section 3 and
// docs/format.md "Garment attributes"). Defaults
// are the middle of the paper's ranges.
struct GarmentAttributes {
  double mass = 0.5;
  double tension = 50;
  double compression = 50;
  double shear = 50;
  double bending = 100;
  double friction = 60;
  double self_friction = 60;

  template <class V>
  void visit(V& v) {
    v("mass", mass, cfg::opt().range(0.001, 10).help("Blender cloth mass (paper: 0.2-0.8)"));
    v("tension", tension, cfg::opt().range(0, 10000).help("tension stiffness (paper: 15-100)"));
    v("compression", compression, cfg::opt().range(0, 10000).help("compression stiffness (paper: 15-100)"));
    v("shear", shear, cfg::opt().range(0, 10000).help("shear stiffness (paper: 15-100)"));
    v("bending", bending, cfg::opt().range(0, 10000).help("bending stiffness (paper: 15-200)"));
    v("friction", friction, cfg::opt().range(0, 80).help("friction against the body (paper: 40-80)"));
    v("self_friction", self_friction,
      cfg::opt().range(0, 80).help("friction against itself and other layers (paper: 40-80)"));
  }
};

// Physical, resolution-independent parameters (SI units).
struct Material {
  double density = 0.25;              // kg/m^2
  double tension_modulus = 1000;      // N/m, 2D Young's modulus for stretching
  double compression_modulus = 1000;  // N/m, the same for compression
  double shear_modulus = 250;         // N/m, in-plane shear
  double bending_rigidity = 2e-5;     // N m
  double friction = 0.6;              // Coulomb coefficient against the body
  double self_friction = 0.6;         // against the garment itself and other layers
};

// Constants of the attribute -> material map: each physical parameter is
// its attribute times a constant (friction: divided by 100), so the map is
// linear and monotone.
struct MaterialMapping {
  double density_per_mass = 0.5;         // (kg/m^2) per unit of Blender mass
  double modulus_per_stiffness = 20;     // (N/m) per unit of tension
  double compression_per_stiffness = 5;  // (N/m) per unit of compression (fabric buckles)
  double shear_per_stiffness = 5;        // (N/m) per unit of shear
  double rigidity_per_bending = 2e-7;    // (N m) per unit of bending
  double friction_per_unit = 0.01;       // Coulomb coefficient per unit of friction

  template <class V>
  void visit(V& v) {
    v("density_per_mass", density_per_mass, cfg::opt().min(1e-6).help("kg/m^2 per unit of mass"));
    v("modulus_per_stiffness", modulus_per_stiffness, cfg::opt().min(0).help("N/m per unit of tension"));
    v("compression_per_stiffness", compression_per_stiffness, cfg::opt().min(0).help("N/m per unit of compression"));
    v("shear_per_stiffness", shear_per_stiffness, cfg::opt().min(0).help("N/m per unit of shear"));
    v("rigidity_per_bending", rigidity_per_bending, cfg::opt().min(0).help("N m per unit of bending"));
    v("friction_per_unit", friction_per_unit, cfg::opt().range(0, 1).help("Coulomb coefficient per unit"));
  }
};

// The map itself. Throws layers::InputError if an attribute is negative or
// the mass is not positive (`what` names the garment in the message).
Material to_material(const GarmentAttributes& attributes, const MaterialMapping& mapping = {},
                     const std::string& what = "garment attributes");

}  // namespace layers::sim
