// Solver dynamics without contact or with the simplest: free fall, sag
// ordering by stiffness, resolution independence, determinism, pins.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>

#include "layers/core/error.h"
#include "scenes.h"

namespace layers::sim {
namespace {

using geometry::Points;
using test::V3;

// A square sheet of side `size` hanging in the xy plane from its top edge
// (all of it, or only the two top corners), centred at x = 0, top at y = 1.
Cloth hanging_sheet(double size, double edge, const GarmentAttributes& a, bool corners_only) {
  const int n = static_cast<int>(std::lround(size / edge));
  ClothOptions o;
  o.name = "sheet";
  if (corners_only)
    o.pinned = {0, n};
  else
    for (int i = 0; i <= n; ++i) o.pinned.push_back(i);
  return Cloth(test::grid(V3(-size / 2, 1.0, 0), V3(size, 0, 0), V3(0, -size, 0), n, n), to_material(a), o);
}

// Steps a solver holding one cloth until it is at rest; returns the centroid.
V3 settle(Solver& s, int frames) {
  for (int f = 0; f < frames; ++f) s.step();
  return test::centroid(s.cloth(0).positions());
}

TEST(Dynamics, FreeFallMatchesHalfGTSquared) {
  SolverConfig c;
  c.air_damping = 0;
  Solver s(c);
  s.add_cloth(Cloth(test::grid(V3(0, 2, 0), V3(0.3, 0, 0), V3(0, 0, 0.3), 6, 6), Material{}));
  const V3 start = test::centroid(s.cloth(0).positions());
  for (int f = 0; f < 30; ++f) s.step();
  const double drop = start.y() - test::centroid(s.cloth(0).positions()).y();
  const double expected = 0.5 * 9.81 * 1.0 * 1.0;
  std::printf("[sim] free fall over 1 s: %.4f m, 0.5 g t^2 = %.4f m (%.3f%% off)\n", drop, expected,
              100 * std::abs(drop / expected - 1));
  EXPECT_NEAR(drop / expected, 1.0, 0.01);
}

TEST(Dynamics, StifferClothSagsLess) {
  // Hung from its two top corners, a sheet sags by stretching; more tension
  // stiffness, less sag. Air damping brings it to rest.
  SolverConfig c;
  c.air_damping = 5;
  double previous = -1;
  for (double tension : {15.0, 40.0, 100.0}) {
    GarmentAttributes a;
    a.tension = a.compression = a.shear = tension;
    Solver s(c);
    s.add_cloth(hanging_sheet(0.4, 0.02, a, true));
    const double sag = 1.0 - settle(s, 60).y();
    std::printf("[sim] sheet hung by its corners, tension %5.1f: centroid %.2f mm below the pins\n", tension,
                1000 * sag);
    if (previous > 0) {
      EXPECT_LT(sag, previous) << "tension " << tension;
    }
    previous = sag;
  }
}

TEST(Dynamics, ResolutionIndependentSheet) {
  // The same sheet at edge e and e/2 hangs to the same shape.
  SolverConfig c;
  c.air_damping = 5;
  V3 centroid[2];
  for (int k = 0; k < 2; ++k) {
    Solver s(c);
    s.add_cloth(hanging_sheet(0.4, k == 0 ? 0.04 : 0.02, GarmentAttributes{}, true));
    centroid[k] = settle(s, 60);
  }
  const double gap = (centroid[0] - centroid[1]).norm();
  std::printf("[sim] corner-hung sheet at e = 4 cm vs 2 cm: centroids %.2f mm apart\n", 1000 * gap);
  EXPECT_LT(gap, 0.01);
}

TEST(Dynamics, ResolutionIndependentGarment) {
  // A garment resting on a body, at edge 3 cm and 1.5 cm.
  V3 centroid[2];
  int vertices[2];
  for (int k = 0; k < 2; ++k) {
    test::DressedCapsule scene;
    scene.edge = k == 0 ? 0.03 : 0.015;
    Solver s = scene.make();
    vertices[k] = s.cloth(0).num_vertices();
    centroid[k] = settle(s, 45);
  }
  const double gap = (centroid[0] - centroid[1]).norm();
  std::printf("[sim] garment on a body at e = 3 cm (%d vertices) vs 1.5 cm (%d): mean positions %.2f mm apart\n",
              vertices[0], vertices[1], 1000 * gap);
  EXPECT_LT(gap, 0.01);
}

// Runs a scene with everything switched on and returns the bytes of the
// final positions of both garments.
std::vector<float> rich_run() {
  test::DressedCapsule scene;
  scene.two_layers = true;
  scene.edge = 0.04;
  scene.body_edge = 0.03;
  Solver s = scene.make();
  const Points rest = s.body().vertices;
  Wind wind;
  wind.direction = V3(0.6, 0, 0.8);
  wind.strength = 300;
  for (int f = 1; f <= 20; ++f) s.step(test::sway(rest, f), f > 8 ? wind : Wind{});
  std::vector<float> out;
  for (int i = 0; i < s.num_cloths(); ++i) {
    const Points p = s.cloth(i).positions();
    out.insert(out.end(), p.data(), p.data() + p.size());
  }
  return out;
}

TEST(Dynamics, SameInputsSameBytes) {
  const std::vector<float> a = rich_run(), b = rich_run();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0);
}

TEST(Dynamics, PinnedVerticesStayAndConfigChecks) {
  Solver s;
  s.add_cloth(hanging_sheet(0.2, 0.05, GarmentAttributes{}, false));
  const Points before = s.cloth(0).positions();
  for (int f = 0; f < 5; ++f) s.step();
  const Points after = s.cloth(0).positions();
  for (int i = 0; i <= 4; ++i) EXPECT_TRUE(after.row(i).isApprox(before.row(i))) << i;
  EXPECT_GT(before(24, 1) - after(24, 1), 0.0);  // the free bottom corner sagged
  SolverConfig bad;
  bad.substeps = 0;
  EXPECT_THROW(s.set_config(bad), InputError);
  EXPECT_THROW(s.cloth(3), Error);
  EXPECT_THROW(s.step(before), InputError);  // no body
}

}  // namespace
}  // namespace layers::sim
