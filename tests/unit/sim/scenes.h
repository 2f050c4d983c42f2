// scenes.h -- small scenes shared by the solver tests: a loose bell-shaped
// garment (a tube with a domed top) hanging on a capsule "body" (the wind
// calibration, resolution and performance cases), optionally with a
// tighter inner garment under it.
#pragma once

#include <cmath>

#include "fixtures.h"
#include "layers/sim/measures.h"
#include "layers/sim/solver.h"

namespace layers::sim::test {

struct DressedCapsule {
  // Body: a capsule of this radius whose cylindrical part spans y 0.6..1.4.
  double body_radius = 0.14, body_edge = 0.02;
  // Outer garment: tube radius, length below the closed top, edge length.
  double outer_radius = 0.19, outer_length = 0.6, edge = 0.03;
  // Optional inner garment (two layers).
  bool two_layers = false;
  double inner_radius = 0.155, inner_length = 0.5;
  GarmentAttributes outer_attributes, inner_attributes;
  SolverConfig config;

  double body_top() const { return 1.4 + body_radius; }
  TriMesh body() const { return capsule(V3(0, 0.6, 0), body_radius, 0.8, body_edge); }
  // The top of the dome rests `gap` above the top of the body.
  TriMesh tube(double radius, double length, double gap) const {
    return bell(V3(0, body_top() + gap - radius - length, 0), radius, length, edge);
  }

  Solver make() const {
    Solver s(config);
    s.set_body(body());
    if (two_layers) {
      s.add_cloth(Cloth(tube(inner_radius, inner_length, config.body_thickness + 0.002), to_material(inner_attributes),
                        ClothOptions("inner", 0)));
    }
    const ClothOptions o("outer", 1);
    const double gap = config.body_thickness + (two_layers ? config.layer_thickness + 0.006 : 0.002);
    s.add_cloth(Cloth(tube(outer_radius, outer_length, gap), to_material(outer_attributes), o));
    return s;
  }
};

// The body of `rest` swaying: at frame f it is turned about the vertical
// axis by `turn` sin(2 pi f / period) radians and shifted sideways by
// `shift` sin(...) metres (30 fps).
inline Points sway(const Points& rest, int frame, double turn = 0.35, double shift = 0.05, double period = 30) {
  const double s = std::sin(2 * 3.14159265358979323846 * frame / period);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(turn * s, V3::UnitY()).toRotationMatrix();
  Points out(rest.rows(), 3);
  for (Eigen::Index i = 0; i < rest.rows(); ++i) {
    const V3 p = r * rest.row(i).cast<double>().transpose() + V3(shift * s, 0, 0);
    out.row(i) = p.cast<float>().transpose();
  }
  return out;
}

// Total garment vertices of a solver.
inline int garment_vertices(const Solver& s) {
  int n = 0;
  for (int i = 0; i < s.num_cloths(); ++i) n += s.cloth(i).num_vertices();
  return n;
}

}  // namespace layers::sim::test
