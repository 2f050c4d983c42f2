// Cloth construction: resolution-independent mass, rest state free of
// elastic forces, resolution-independent bending energy, input checks.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fixtures.h"
#include "layers/core/error.h"
#include "layers/sim/cloth.h"
#include "layers/sim/solver.h"

namespace layers::sim {
namespace {

using geometry::Points;
using geometry::TriMesh;
using test::V3;

TriMesh square(double size, int n) { return test::grid(V3(0, 0, 0), V3(size, 0, 0), V3(0, size, 0), n, n); }

TEST(Cloth, MassIsDensityTimesAreaAtAnyResolution) {
  Material m;
  m.density = 0.3;
  for (int n : {4, 9, 20}) {
    const Cloth c(square(0.5, n), m);
    EXPECT_NEAR(c.total_mass(), 0.3 * 0.25, 1e-9) << n;
    // A vertex carries a third of its faces' area: between 2/3 and 4/3 of a
    // grid cell here (valence 4 or 8), whatever the resolution.
    const double cell = 0.3 * (0.5 / n) * (0.5 / n);
    EXPECT_NEAR(c.masses().maxCoeff(), 4.0 / 3.0 * cell, 1e-9) << n;
  }
}

TEST(Cloth, RestStateHasNoElasticForces) {
  SolverConfig config;
  config.gravity = {0, 0, 0};
  config.air_damping = 0;
  Solver solver(config);
  TriMesh rest = square(0.4, 8);
  const int i = solver.add_cloth(Cloth(rest, Material{}));
  for (int f = 0; f < 5; ++f) solver.step();
  EXPECT_LT(test::mean_distance(solver.cloth(i).positions(), rest.vertices), 1e-7);
}

// Wrapping a flat sheet isometrically onto a cylinder of radius R gives a
// bending energy 0.5 * B * sum(weight |c|^2) that converges with resolution
// (and vanishes when flat).
double wrapped_bending_sum(int n, double radius) {
  const double w = 0.3, h = 0.2;
  TriMesh flat = test::grid(V3(0, 0, 0), V3(w, 0, 0), V3(0, h, 0), n, n * 2 / 3);
  const Cloth cloth(flat, Material{});
  Vec3s x(cloth.num_vertices());
  for (int i = 0; i < cloth.num_vertices(); ++i) {
    const V3 p = flat.vertices.row(i).cast<double>().transpose();
    const double a = p.x() / radius;
    x[i] = V3(radius * std::sin(a), p.y(), radius * (1 - std::cos(a)));
  }
  double flat_sum = 0, sum = 0;
  for (const BendingElement& b : cloth.bending()) {
    V3 c = V3::Zero(), c0 = V3::Zero();
    for (int j = 0; j < 4; ++j) {
      c += b.k[j] * x[b.v[j]];
      c0 += b.k[j] * cloth.rest_positions().row(b.v[j]).cast<double>().transpose();
    }
    sum += 0.5 * b.weight * c.squaredNorm();
    flat_sum += 0.5 * b.weight * c0.squaredNorm();
  }
  EXPECT_LT(flat_sum, 1e-10);
  return sum;
}

TEST(Cloth, BendingEnergyIsResolutionIndependent) {
  const double radius = 0.1;
  const double coarse = wrapped_bending_sum(12, radius), fine = wrapped_bending_sum(24, radius),
               finer = wrapped_bending_sum(48, radius);
  // Continuum: integral of 0.5 * kappa^2 over the area (kappa = 1/R).
  const double reference = 0.5 * 0.3 * 0.2 / (radius * radius);
  std::printf(
      "[sim] bending energy / B of a sheet wrapped on R=0.1 m: %.4f (e=2.5cm) %.4f (e=1.25cm) %.4f "
      "(e=0.63cm), continuum 0.5*A/R^2 = %.4f\n",
      coarse, fine, finer, reference);
  EXPECT_NEAR(coarse / finer, 1.0, 0.1);
  EXPECT_NEAR(fine / finer, 1.0, 0.05);
  EXPECT_NEAR(finer / reference, 1.0, 0.05);
}

TEST(Cloth, RejectsBadInput) {
  TriMesh m = square(0.2, 2);
  m.faces(0, 1) = 99;
  EXPECT_THROW(Cloth(m, Material{}), InputError);
  m = square(0.2, 2);
  m.vertices.row(4) = m.vertices.row(3);  // two faces collapse
  EXPECT_THROW(Cloth(m, Material{}), InputError);
  ClothOptions o;
  o.pinned = {100};
  EXPECT_THROW(Cloth(square(0.2, 2), Material{}, o), InputError);
  Cloth c(square(0.2, 2), Material{});
  EXPECT_THROW(c.set_positions(Points::Zero(3, 3)), InputError);
  Points nan = c.positions();
  nan(0, 0) = std::nanf("");
  EXPECT_THROW(c.set_positions(nan), InputError);
}

TEST(Cloth, UvAxesFollowTheLayout) {
  // UVs rotated by 90 degrees: warp (+u) along world y.
  TriMesh m = square(0.2, 2);
  ClothOptions o;
  o.uv.resize(m.num_vertices(), 2);
  for (int i = 0; i < m.num_vertices(); ++i) o.uv.row(i) << m.vertices(i, 1), -m.vertices(i, 0);
  o.uv_faces = m.faces;
  const Cloth c(m, Material{}, o);
  for (const MembraneElement& e : c.membrane()) {
    V3 fu = V3::Zero();
    for (int k = 0; k < 3; ++k) fu += e.wu[k] * c.state().x[e.v[k]];
    EXPECT_NEAR(fu.y(), 1.0, 1e-6);
    EXPECT_NEAR(fu.x(), 0.0, 1e-6);
  }
}

}  // namespace
}  // namespace layers::sim
