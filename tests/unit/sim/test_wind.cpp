// Wind: quaternion convention, schedules, face forces, the push downwind
// and the calibration on a garment (strength 50 calm, 400 strong).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "layers/core/error.h"
#include "scenes.h"

namespace layers::sim {
namespace {

using geometry::Points;
using test::V3;

TEST(Wind, QuaternionRotatesPlusZOntoTheDirection) {
  EXPECT_TRUE(Wind::from_rotation({1, 0, 0, 0}, 10).direction.isApprox(V3(0, 0, 1)));
  // 90 degrees about y takes +z to +x.
  const double s = std::sqrt(0.5);
  EXPECT_TRUE(Wind::from_rotation({s, 0, s, 0}, 10).direction.isApprox(V3(1, 0, 0), 1e-12));
  for (const V3& d : {V3(1, 0, 0), V3(0, -1, 0), V3(0.3, 0.4, -0.866).normalized(), V3(0, 0, -1)}) {
    Wind w;
    w.direction = d;
    w.strength = 7;
    const Wind back = Wind::from_rotation(w.rotation(), w.strength);
    EXPECT_TRUE(back.direction.isApprox(d, 1e-9)) << d.transpose();
    EXPECT_NEAR(w.rotation().norm(), 1.0, 1e-12);
  }
  EXPECT_THROW(Wind::from_rotation({0, 0, 0, 0}, 1), InputError);
}

TEST(Wind, ScheduleIsConstantWithinSpans) {
  Wind east, up;
  east.direction = V3(1, 0, 0);
  east.strength = 300;
  up.direction = V3(0, 1, 0);
  up.strength = 20;
  const WindSchedule schedule({{10, 20, up}, {0, 5, east}});
  EXPECT_DOUBLE_EQ(schedule.at(0).strength, 300);
  EXPECT_DOUBLE_EQ(schedule.at(4).strength, 300);
  EXPECT_TRUE(schedule.at(5).calm());
  EXPECT_TRUE(schedule.at(12).direction.isApprox(V3(0, 1, 0)));
  EXPECT_TRUE(schedule.at(20).calm());
  EXPECT_THROW(WindSchedule({{0, 10, east}, {5, 15, up}}), InputError);  // overlap
  EXPECT_THROW(WindSchedule({{3, 3, east}}), InputError);                // empty
  Wind bad = east;
  bad.direction = V3(2, 0, 0);
  EXPECT_THROW(WindSchedule({{0, 1, bad}}), InputError);
}

TEST(Wind, FaceForceIsDownwindFromEitherSide) {
  const Vec3s x = {V3(0, 0, 0), V3(1, 0, 0), V3(0, 1, 0)};  // area 0.5, normal +z
  Wind w;
  w.direction = V3(0, 0.6, 0.8);
  w.strength = 100;
  const double k = 0.01;  // Pa per unit: 1 Pa
  Vec3s f1(3, V3::Zero()), f2(3, V3::Zero()), f3(3, V3::Zero());
  add_wind_forces({{0, 1, 2}}, x, w, k, f1);
  add_wind_forces({{0, 2, 1}}, x, w, k, f2);  // flipped winding
  V3 total = f1[0] + f1[1] + f1[2];
  // P A (n.w) n = 1 Pa * 0.5 m^2 * 0.8 * +z.
  EXPECT_TRUE(total.isApprox(V3(0, 0, 0.4), 1e-12)) << total.transpose();
  EXPECT_TRUE((f2[0] + f2[1] + f2[2]).isApprox(total, 1e-12));
  EXPECT_GT(total.dot(w.direction), 0);
  w.direction = V3(1, 0, 0);  // parallel to the face
  add_wind_forces({{0, 1, 2}}, x, w, k, f3);
  EXPECT_LT((f3[0] + f3[1] + f3[2]).norm(), 1e-15);
}

TEST(Wind, PushesClothDownwind) {
  // A curtain hung from its top edge; wind blows through it along +z. The
  // curtain swings like a pendulum driven by the wind, so the displacement
  // is averaged over the second.
  double previous = 0;
  for (double strength : {0.0, 100.0, 400.0}) {
    Solver s;
    const int n = 10;
    ClothOptions o;
    for (int i = 0; i <= n; ++i) o.pinned.push_back(i);
    s.add_cloth(Cloth(test::grid(V3(-0.2, 1, 0), V3(0.4, 0, 0), V3(0, -0.4, 0), n, n), to_material({}), o));
    Wind w;
    w.direction = V3(0, 0, 1);
    w.strength = strength;
    double downwind = 0;
    for (int f = 0; f < 30; ++f) {
      s.step(w);
      downwind += test::centroid(s.cloth(0).positions()).z() / 30;
    }
    std::printf("[sim] curtain in wind %3.0f: mean displacement downwind over 1 s %.1f mm\n", strength,
                1000 * downwind);
    if (strength > 0) {
      EXPECT_GT(downwind, previous) << strength;
    }
    previous = downwind;
  }
  EXPECT_GT(previous, 0.01);
}

TEST(Wind, CalibratedCalmAndStrongOnAGarment) {
  // A loose garment hanging on a body, settled for 1 s; then 1 s with or
  // without wind from the side. Mean vertex displacement against the calm
  // run: strength 50 is calm (< 1 cm), 400 strong (>= 3 cm).
  for (double mass : {0.2, 0.5, 0.8}) {
    test::DressedCapsule scene;
    scene.outer_attributes.mass = mass;
    const auto run = [&](double strength) {
      Solver s = scene.make();
      for (int f = 0; f < 30; ++f) s.step();
      Wind w;
      w.direction = V3(1, 0, 0);
      w.strength = strength;
      for (int f = 0; f < 30; ++f) s.step(w);
      return s.cloth(0).positions();
    };
    const Points calm = run(0);
    double moved[3];
    const double strengths[3] = {50, 250, 400};
    for (int k = 0; k < 3; ++k) moved[k] = test::mean_distance(run(strengths[k]), calm);
    std::printf(
        "[sim] wind calibration, mass %.1f (%.2f kg/m^2): mean displacement after 1 s at 50 / 250 / 400: "
        "%.1f / %.1f / %.1f mm\n",
        mass, to_material(scene.outer_attributes).density, 1000 * moved[0], 1000 * moved[1], 1000 * moved[2]);
    EXPECT_GE(moved[2], 0.03) << "mass " << mass;
    if (mass >= 0.5) {
      EXPECT_LT(moved[0], 0.01) << "mass " << mass;
    }
    EXPECT_LT(moved[0], moved[1]);
  }
}

}  // namespace
}  // namespace layers::sim
