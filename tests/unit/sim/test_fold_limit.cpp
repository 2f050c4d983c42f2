// The fold cap (internal FoldLimiter, SolverConfig::max_fold): a hinge
// folded past the cap is opened to it, across the hinge line only; folds
// within the cap and hinges whose rest shape is folded further are left
// alone; and a solver frame with the setting on ends within the cap (with
// it off, the fold stays).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "fixtures.h"
#include "fold_limit.h"
#include "layers/sim/cloth.h"
#include "layers/sim/solver.h"

namespace layers::sim {
namespace {

using test::V3;

constexpr double kPi = 3.14159265358979323846;

// Largest angle (degrees) between the normals of two faces sharing an edge.
double max_fold_deg(const Cloth& cloth, const Vec3s& x) {
  double worst = 0;
  for (const BendingElement& b : cloth.bending()) {
    const Vec3 n2 = (x[b.v[1]] - x[b.v[0]]).cross(x[b.v[2]] - x[b.v[0]]).normalized();
    const Vec3 n3 = (x[b.v[3]] - x[b.v[0]]).cross(x[b.v[1]] - x[b.v[0]]).normalized();
    worst = std::max(worst, std::acos(std::clamp(n2.dot(n3), -1.0, 1.0)) * 180 / kPi);
  }
  return worst;
}

// A 4 x 2 cm sheet of 1 cm cells in the z = 0 plane; the vertices right of
// x = 2 cm are turned about that line by `angle` degrees (over the left half).
Vec3s folded(const geometry::TriMesh& flat, double angle) {
  const double a = angle * kPi / 180;
  Vec3s x;
  for (Eigen::Index i = 0; i < flat.vertices.rows(); ++i) {
    Vec3 p = flat.vertices.row(i).cast<double>().transpose();
    const double d = p.x() - 0.02;
    if (d > 1e-9) p = Vec3(0.02 + d * std::cos(a), p.y(), d * std::sin(a));
    x.push_back(p);
  }
  return x;
}

geometry::TriMesh sheet() { return test::grid(V3(0, 0, 0), V3(0.04, 0, 0), V3(0, 0.02, 0), 4, 2); }

TEST(FoldLimit, OpensFoldsPastTheCapAndLeavesTheRest) {
  const geometry::TriMesh flat = sheet();
  Cloth cloth(flat, Material{});
  detail::FoldLimiter limiter;

  Cloth::State state = cloth.state();
  state.x = folded(flat, 170);
  ASSERT_GT(max_fold_deg(cloth, state.x), 165);
  const int sweeps = limiter.apply(cloth, state, 120 * kPi / 180, 50);
  EXPECT_TRUE(limiter.converged());
  EXPECT_LT(sweeps, 50);
  const double after = max_fold_deg(cloth, state.x);
  EXPECT_LE(after, 121);
  EXPECT_GT(after, 90);  // opened to the cap, not flattened

  // A 60 degree fold is within a 120 degree cap: nothing moves.
  Cloth::State mild = cloth.state();
  mild.x = folded(flat, 60);
  const Vec3s before = mild.x;
  EXPECT_EQ(limiter.apply(cloth, mild, 120 * kPi / 180, 50), 1);
  EXPECT_TRUE(limiter.converged());
  for (std::size_t i = 0; i < before.size(); ++i) EXPECT_EQ(mild.x[i], before[i]);
}

TEST(FoldLimit, ARestShapeFoldedFurtherKeepsItsAngle) {
  // Cut with a 150 degree fold (a seam): a 90 degree cap does not open it.
  const geometry::TriMesh flat = sheet();
  geometry::TriMesh rest = flat;
  const Vec3s x150 = folded(flat, 150);
  for (std::size_t i = 0; i < x150.size(); ++i) rest.vertices.row(i) = x150[i].cast<float>().transpose();
  Cloth cloth(rest, Material{});
  detail::FoldLimiter limiter;
  Cloth::State state = cloth.state();
  EXPECT_EQ(limiter.apply(cloth, state, 90 * kPi / 180, 50), 1);
  EXPECT_NEAR(max_fold_deg(cloth, state.x), 150, 0.5);
  // Folded further than its rest shape, it opens back to about it.
  state.x = folded(flat, 175);
  limiter.apply(cloth, state, 90 * kPi / 180, 50);
  EXPECT_TRUE(limiter.converged());
  EXPECT_LE(max_fold_deg(cloth, state.x), 151);
}

TEST(FoldLimit, StaggeredWingsOpenAcrossTheHingeOnly) {
  // One hinge along x with its wings at different places along it (as in
  // most triangle meshes): the fold opens to the cap and the wings keep
  // their positions along the hinge.
  const geometry::TriMesh flat =
      test::make_mesh({V3(0, 0, 0), V3(0.01, 0, 0), V3(0, 0.01, 0), V3(0.01, -0.01, 0)}, {{0, 1, 2}, {1, 0, 3}});
  Cloth cloth(flat, Material{});
  ASSERT_EQ(cloth.bending().size(), 1u);
  Cloth::State state = cloth.state();
  const double a = 170 * kPi / 180;
  state.x[3] = V3(0.01, -0.01 * std::cos(a), -0.01 * std::sin(a));  // turned about x by 170 degrees
  ASSERT_NEAR(max_fold_deg(cloth, state.x), 170, 1e-6);
  detail::FoldLimiter limiter;
  // One sweep takes it most of the way (the push also moves the wings off
  // the line, so the angle it reaches is a little past the cap)...
  limiter.apply(cloth, state, 120 * kPi / 180, 1);
  EXPECT_LT(max_fold_deg(cloth, state.x), 130);
  // ...and a few more to the cap.
  limiter.apply(cloth, state, 120 * kPi / 180, 50);
  EXPECT_TRUE(limiter.converged());
  EXPECT_NEAR(max_fold_deg(cloth, state.x), 120, 1);
  EXPECT_NEAR(state.x[2].x(), 0.0, 1e-12);
  EXPECT_NEAR(state.x[3].x(), 0.01, 1e-12);
}

TEST(FoldLimit, TheSolverAppliesItWhenOn) {
  const geometry::TriMesh flat = sheet();
  auto fold_after_a_frame = [&](double max_fold) {
    SolverConfig config;
    config.gravity = {0, 0, 0};
    config.max_fold = max_fold;
    Solver solver(config);
    Cloth cloth(flat, Material{});
    const Vec3s x = folded(flat, 170);
    geometry::Points p(static_cast<Eigen::Index>(x.size()), 3);
    for (std::size_t i = 0; i < x.size(); ++i) p.row(static_cast<Eigen::Index>(i)) = x[i].cast<float>().transpose();
    cloth.set_positions(p);
    const int id = solver.add_cloth(std::move(cloth));
    solver.step(Wind{});
    return max_fold_deg(solver.cloth(id), solver.cloth(id).state().x);
  };
  const double off = fold_after_a_frame(0), on = fold_after_a_frame(100);
  EXPECT_GT(off, 150);  // soft bending alone barely opens it in a frame
  EXPECT_LE(on, 102);
}

}  // namespace
}  // namespace layers::sim
