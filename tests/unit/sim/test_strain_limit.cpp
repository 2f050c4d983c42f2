// The strain cap (internal StrainLimiter): it converges where Gauss-Seidel
// needs many sweeps (the stretch has to travel along the cloth against the
// sweep order; later sweeps visit only the edges around what moved) and
// says when its sweeps ran out first (the solver counts those calls), and
// held vertices (in contact) give way less than free ones.
#include <gtest/gtest.h>

#include <cstdio>

#include "fixtures.h"
#include "layers/sim/cloth.h"
#include "layers/sim/solver.h"
#include "strain_limit.h"

namespace layers::sim {
namespace {

using test::V3;

// A strip 2 cm wide along x, 12 cm long, 1 cm edges, stretched by 30% along
// x and pinned at its far end (x = 0.156), so each sweep in index order (from
// x = 0) passes the correction on by one edge only.
Cloth stretched_strip() {
  geometry::TriMesh rest = test::grid(V3(0, 0, 0), V3(0.12, 0, 0), V3(0, 0.02, 0), 12, 2);
  ClothOptions options;
  for (Eigen::Index i = 0; i < rest.vertices.rows(); ++i)
    if (rest.vertices(i, 0) > 0.1199f) options.pinned.push_back(static_cast<int>(i));
  Cloth cloth(rest, Material{}, options);
  geometry::Points x = rest.vertices;
  x.col(0) *= 1.3f;
  cloth.set_positions(x);
  return cloth;
}

double max_stretch(const Cloth& c) {
  double worst = 0;
  const auto& x = c.state().x;
  for (Eigen::Index e = 0; e < c.edges().rows(); ++e)
    worst = std::max(worst, (x[c.edges()(e, 0)] - x[c.edges()(e, 1)]).norm() / c.rest_lengths()[e] - 1);
  return worst;
}

TEST(StrainLimit, ConvergesWhereManySweepsAreNeeded) {
  Cloth cloth = stretched_strip();
  detail::StrainLimiter limiter;
  // Too few sweeps: it stops with edges still over and says so.
  Cloth::State cut_short = cloth.state();
  EXPECT_EQ(limiter.apply(cloth, cut_short, 0.08, 3), 3);
  EXPECT_FALSE(limiter.converged());
  Cloth::State state = cloth.state();
  const int sweeps = limiter.apply(cloth, state, 0.08, 1000);
  EXPECT_TRUE(limiter.converged());
  std::printf("[sim] strip pinned at the far end: capped in %d sweeps\n", sweeps);
  EXPECT_GT(sweeps, 5);    // the correction travels edge by edge...
  EXPECT_LT(sweeps, 200);  // ...and converges within the old default budget
  Cloth capped = cloth;
  capped.set_velocities(geometry::Points::Zero(cloth.num_vertices(), 3));
  geometry::Points x(cloth.num_vertices(), 3);
  for (int i = 0; i < cloth.num_vertices(); ++i) x.row(i) = state.x[i].cast<float>().transpose();
  capped.set_positions(x);
  EXPECT_LE(max_stretch(capped), 1.08 * 1.005 - 1 + 1e-9);  // within the slack
  EXPECT_GT(max_stretch(cloth), 0.29);
  // The pinned end did not move; the free end came most of the way back.
  EXPECT_EQ(state.x[cloth.num_vertices() - 1], cloth.state().x[cloth.num_vertices() - 1]);
  EXPECT_GT(state.x[0].x(), 0.156 - 0.12 * 1.08 * 1.005 - 1e-6);
  // Capped again, nothing moves.
  const Cloth::State before = state;
  EXPECT_EQ(limiter.apply(cloth, state, 0.08, 1000), 1);
  for (std::size_t i = 0; i < state.x.size(); ++i) EXPECT_EQ(state.x[i], before.x[i]);
}

TEST(StrainLimit, HeldVerticesGiveWayLess) {
  // One over-long edge between a held and a free vertex: the free one takes
  // five sixths of the correction (a held vertex a fifth of its share).
  geometry::TriMesh tri = test::make_mesh({V3(0, 0, 0), V3(0.01, 0, 0), V3(0.005, 0.01, 0)}, {{0, 1, 2}});
  Cloth cloth(tri, Material{});
  Cloth::State state = cloth.state();
  state.x[1] = V3(0.0115, 0, 0);  // edge 0-1 +15%, edge 1-2 +6.7% (within the cap)
  std::vector<std::uint8_t> held = {1, 0, 0};
  detail::StrainLimiter limiter;
  limiter.apply(cloth, state, 0.08, 100, &held);
  // Over-relaxed: shortened by 1.8 times its excess over the cap.
  EXPECT_NEAR((state.x[1] - state.x[0]).norm(), 0.0108 - 0.8 * (0.0115 - 0.0108), 1e-9);
  const double moved0 = state.x[0].x(), moved1 = 0.0115 - state.x[1].x();
  EXPECT_GT(moved0, 0);
  EXPECT_NEAR(moved1 / moved0, 5.0, 0.3);  // equal masses
}

TEST(StrainLimit, TheSolverCountsCapsThatRanOutOfSweeps) {
  // A cap of 0.1% on the stretched strip: one sweep cannot meet it, a large
  // budget can; StepTimings::cap_unfinished counts the calls cut short.
  for (const int sweeps : {1, 100000}) {
    SolverConfig config;
    config.max_strain = 0.001;
    config.substeps = 2;
    config.strain_sweeps = sweeps;
    Solver solver(config);
    solver.add_cloth(stretched_strip());
    solver.step();
    const long unfinished = solver.timings().cap_unfinished;
    std::printf("[sim] strain_sweeps %d: %ld of 2 cap calls ran out\n", sweeps, unfinished);
    if (sweeps == 1)
      EXPECT_EQ(unfinished, 2);
    else
      EXPECT_EQ(unfinished, 0);
  }
}

}  // namespace
}  // namespace layers::sim
