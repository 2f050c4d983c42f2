// Tests of the continuous-collision safety pass (collision_pass.h, ccd.h):
// the narrow phase on hand-made pairs, the pass on sheets displaced at
// random (no crossings at the end, ever), and the solver with the pass on:
// sheets driven through each other at speed, two layers pinched between
// two plates, a thin strip crumpled onto itself, determinism; impact zones
// and the body yielding where it pinches cloth.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <tuple>

#include "body_collider.h"
#include "body_pinch.h"
#include "ccd.h"
#include "collision_pass.h"
#include "fixtures.h"
#include "layers/geometry/intersect.h"
#include "layers/geometry/pinch.h"
#include "layers/geometry/topology.h"
#include "layers/sim/measures.h"
#include "layers/sim/solver.h"

namespace layers::sim {
namespace {

using test::grid;
using test::V3;

detail::Sweep sweep(std::array<V3, 4> from, std::array<V3, 4> to, bool edge_edge) {
  detail::Sweep s;
  s.edge_edge = edge_edge;
  for (int k = 0; k < 4; ++k) {
    s.x0[k] = from[k];
    s.dx[k] = to[k] - from[k];
  }
  return s;
}

TEST(Ccd, AVertexThroughATriangleHitsBeforeItGetsThere) {
  const V3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  const auto s = sweep({V3(0.2, 0.2, 1), a, b, c}, {V3(0.2, 0.2, -1), a, b, c}, false);
  double toi = -1;
  ASSERT_TRUE(detail::sweep_hits(s, 1e-3, toi));
  EXPECT_GT(toi, 0.4);
  EXPECT_LT(toi, 0.5);
  EXPECT_GE(detail::sweep_distance(s, toi), 1e-3);
}

TEST(Ccd, AVertexPassingBesideATriangleOrMovingWithItDoesNotHit) {
  const V3 a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  double toi;
  // Beside the triangle, through its plane.
  EXPECT_FALSE(detail::sweep_hits(sweep({V3(2, 2, 1), a, b, c}, {V3(2, 2, -1), a, b, c}, false), 1e-3, toi));
  // 1 mm above it, everything translated together, fast.
  const V3 m(5, -3, 7);
  EXPECT_FALSE(detail::sweep_hits(
      sweep({V3(0.2, 0.2, 1e-3), a, b, c}, {V3(0.2, 0.2, 1e-3) + m, a + m, b + m, c + m}, false), 1e-4, toi));
  // The triangle sweeps up through a resting vertex.
  EXPECT_TRUE(detail::sweep_hits(sweep({V3(0.2, 0.2, 0.5), a, b, c},
                                       {V3(0.2, 0.2, 0.5), a + V3(0, 0, 1), b + V3(0, 0, 1), c + V3(0, 0, 1)}, false),
                                 1e-4, toi));
}

TEST(Ccd, CrossingEdgesHitAndParallelEdgesApartDoNot) {
  double toi;
  // Edge along x at z = 1 moving down through an edge along y at z = 0.
  EXPECT_TRUE(detail::sweep_hits(sweep({V3(-1, 0, 1), V3(1, 0, 1), V3(0, -1, 0), V3(0, 1, 0)},
                                       {V3(-1, 0, -1), V3(1, 0, -1), V3(0, -1, 0), V3(0, 1, 0)}, true),
                                 1e-4, toi));
  // The same motion past the end of the other edge.
  EXPECT_FALSE(detail::sweep_hits(sweep({V3(-1, 3, 1), V3(1, 3, 1), V3(0, -1, 0), V3(0, 1, 0)},
                                        {V3(-1, 3, -1), V3(1, 3, -1), V3(0, -1, 0), V3(0, 1, 0)}, true),
                                  1e-4, toi));
  // Parallel edges sliding along each other 1 cm apart.
  EXPECT_FALSE(detail::sweep_hits(sweep({V3(0, 0, 0.01), V3(1, 0, 0.01), V3(0, 0, 0), V3(1, 0, 0)},
                                        {V3(0.5, 0, 0.01), V3(1.5, 0, 0.01), V3(0, 0, 0), V3(1, 0, 0)}, true),
                                  1e-3, toi));
}

TEST(Ccd, ClosestPointsOfDegenerateFeatures) {
  std::array<double, 3> b;
  // A collapsed triangle (all on a line): the nearest point of the segment.
  const double d2 = detail::point_triangle_distance2(V3(0.5, 1, 0), V3(0, 0, 0), V3(1, 0, 0), V3(2, 0, 0), &b);
  EXPECT_NEAR(d2, 1.0, 1e-12);
  double s, t;
  EXPECT_NEAR(detail::segment_segment_distance2(V3(0, 0, 1), V3(0, 0, 1), V3(-1, 0, 0), V3(1, 0, 0), &s, &t), 1.0,
              1e-12);
  EXPECT_NEAR(t, 0.5, 1e-12);
}

// Crossing face pairs between every two cloths, and within each cloth
// that has self-contact (what the pass guarantees to keep at zero).
long cloth_crossings(const std::vector<Cloth>& cloths, const std::vector<Vec3s>& positions) {
  std::vector<geometry::TriMesh> meshes;
  for (std::size_t c = 0; c < cloths.size(); ++c) {
    geometry::TriMesh m;
    m.faces = cloths[c].faces();
    m.vertices.resize(static_cast<Eigen::Index>(positions[c].size()), 3);
    for (std::size_t i = 0; i < positions[c].size(); ++i)
      m.vertices.row(static_cast<Eigen::Index>(i)) = positions[c][i].cast<float>().transpose();
    meshes.push_back(m);
  }
  long pairs = 0;
  for (std::size_t a = 0; a < meshes.size(); ++a) {
    for (std::size_t b = a + 1; b < meshes.size(); ++b) pairs += geometry::crossings(meshes[a], meshes[b]).pairs;
    if (cloths[a].self_contact()) pairs += geometry::self_crossings(geometry::FaceTree(meshes[a])).pairs;
  }
  return pairs;
}

TEST(CollisionPass, RandomDisplacementsNeverEndCrossed) {
  // Two stacked sheets (5 mm apart) and a third sheet with self-contact
  // folded over them; every vertex is thrown up to 3 cm at random, twenty
  // times in a row, each time from where the pass left it.
  std::vector<Cloth> cloths;
  cloths.emplace_back(grid(V3(0, 0, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 10, 10), Material{}, ClothOptions("inner", 0));
  cloths.emplace_back(grid(V3(0, 0.005, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 10, 10), Material{},
                      ClothOptions("outer", 1));
  cloths.emplace_back(grid(V3(0, 0.012, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 9, 9), Material{},
                      ClothOptions("folded", 1, true));
  std::vector<Cloth::State> states;
  for (const Cloth& c : cloths) states.push_back(c.state());
  std::vector<Cloth::State*> ptr;
  for (auto& s : states) ptr.push_back(&s);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.03, 0.03);
  long reverted = 0, pairs = 0, zoned = 0;
  detail::CollisionPass pass;
  for (int round = 0; round < 20; ++round) {
    std::vector<Vec3s> push;
    std::vector<std::vector<std::uint8_t>> back;
    for (auto& s : states) {
      s.x_start = s.x;
      for (Vec3& p : s.x) p += Vec3(u(rng), u(rng), u(rng));
      push.emplace_back(s.x.size(), Vec3::Zero());
      back.emplace_back(s.x.size(), 0);
    }
    const detail::CollisionPassStats st = pass.run(cloths, ptr, {}, 5e-4, 4, push, back);
    reverted += st.reverted;
    zoned += st.zoned;
    pairs += st.pairs;
    std::vector<Vec3s> now;
    for (auto& s : states) now.push_back(s.x);
    ASSERT_EQ(cloth_crossings(cloths, now), 0) << "round " << round;
    EXPECT_EQ(st.yielded, 0);
  }
  EXPECT_GT(pairs, 0);     // the displacements did collide
  EXPECT_GT(zoned, 0);     // ... hard enough for impact zones
  EXPECT_GT(reverted, 0);  // ... and for the fail-safe to act
}

TEST(CollisionPass, ClothPinchedBetweenTwoBodyPartsMakesTheBodyYield) {
  // The body: two plates closing from 10 mm to 1 mm apart in one substep,
  // a sheet at rest between them. Each plate alone would push the sheet
  // out of its way, into the other. Where the body is in a pinch zone (here
  // all of it: two parts closer than the pinch distance) the plates yield
  // and the sheet does not move; told of no zone, the pass pushes it.
  const geometry::TriMesh lower = grid(V3(-0.05, -0.005, -0.05), V3(0, 0, 0.3), V3(0.3, 0, 0), 6, 6);
  const geometry::TriMesh upper = grid(V3(-0.05, 0.005, -0.05), V3(0.3, 0, 0), V3(0, 0, 0.3), 6, 6);
  const geometry::TriMesh body = geometry::concatenate({lower, upper});
  Vec3s start, end;
  for (Eigen::Index i = 0; i < body.vertices.rows(); ++i) {
    const Vec3 p = body.vertices.row(i).cast<double>().transpose();
    start.push_back(p);
    end.push_back(Vec3(p.x(), 0.1 * p.y(), p.z()));
  }
  std::vector<std::array<int, 3>> faces;
  for (Eigen::Index f = 0; f < body.faces.rows(); ++f)
    faces.push_back({body.faces(f, 0), body.faces(f, 1), body.faces(f, 2)});
  const geometry::Edges edges = geometry::unique_edges(body.faces);
  detail::SweptBody swept;
  swept.start = &start;
  swept.end = &end;
  swept.faces = &faces;
  swept.edges = &edges;

  const std::vector<std::uint8_t> pinch(start.size(), 1);

  std::vector<Cloth> cloths;
  cloths.emplace_back(grid(V3(0, 0, 0), V3(0, 0, 0.2), V3(0.2, 0, 0), 8, 8), Material{}, ClothOptions("sheet", 0));
  for (const bool zone : {true, false}) {
    swept.pinch = zone ? &pinch : nullptr;
    std::vector<Cloth::State> states{cloths[0].state()};
    states[0].x_start = states[0].x;
    std::vector<Cloth::State*> ptr{&states[0]};
    std::vector<Vec3s> push{Vec3s(states[0].x.size(), Vec3::Zero())};
    std::vector<std::vector<std::uint8_t>> back{std::vector<std::uint8_t>(states[0].x.size(), 0)};
    detail::CollisionPass pass;
    const detail::CollisionPassStats st = pass.run(cloths, ptr, swept, 5e-4, 16, push, back);
    EXPECT_GT(st.pairs, 0);
    EXPECT_GT(st.yielded, 0);
    double moved = 0;
    for (std::size_t i = 0; i < states[0].x.size(); ++i)
      moved = std::max(moved, (states[0].x[i] - states[0].x_start[i]).norm());
    if (zone) {
      EXPECT_EQ(moved, 0.0);
    } else {
      EXPECT_GT(moved, 1e-4);
    }
  }
}

TEST(BodyPinch, TheBodyYieldsOnlyWhereEveryFaceIsPinchedAtBothEndsOfTheFrame) {
  // The body: a 10 cm plate and a 4 cm plate 12 mm over its corner (two
  // parts closer than the 18 mm pinch distance), cloth lying between them.
  const auto body_at = [](double height) {
    return geometry::concatenate({grid(V3(0, 0, 0), V3(0, 0, 0.1), V3(0.1, 0, 0), 10, 10),
                                  grid(V3(0, height, 0), V3(0.04, 0, 0), V3(0, 0, 0.04), 4, 4)});
  };
  const geometry::TriMesh body = body_at(0.012);
  std::vector<Cloth> cloths;
  cloths.emplace_back(grid(V3(0, 0.006, 0), V3(0, 0, 0.04), V3(0.04, 0, 0), 4, 4), Material{},
                      ClothOptions("sheet", 0));
  detail::BodyCollider collider;
  collider.reset(body);
  detail::BodyPinch pinch;
  // Standing still: a vertex yields when every face around it is in a
  // zone of geometry::pinch_zones_under() (the measures' zones).
  collider.begin_frame(nullptr);
  const std::vector<std::uint8_t> still = pinch.update(collider, body.faces, cloths, 0.018);
  geometry::Points stacked(cloths[0].num_vertices(), 3);
  for (int i = 0; i < cloths[0].num_vertices(); ++i) stacked.row(i) = cloths[0].state().x[i].cast<float>();
  const geometry::PinchZones zones = geometry::pinch_zones_under(body, {}, 0.018, stacked, 0.01);
  long yielding = 0;
  for (int v = 0; v < body.num_vertices(); ++v) {
    bool all = true;
    for (int f = 0; f < body.num_faces(); ++f)
      for (int k = 0; k < 3; ++k)
        if (body.faces(f, k) == v && !zones.faces[f]) all = false;
    EXPECT_EQ(still[v] != 0, all) << v;
    yielding += still[v];
  }
  EXPECT_GT(yielding, 25);  // at least the upper plate's 5 x 5 vertices
  // The upper plate lifts to 5 cm in this frame: pinched at the start, not
  // at the end, so the body does not yield anywhere.
  const geometry::TriMesh lifted = body_at(0.05);
  collider.begin_frame(&lifted.vertices);
  const std::vector<std::uint8_t> lifting = pinch.update(collider, body.faces, cloths, 0.018);
  EXPECT_EQ(std::count(lifting.begin(), lifting.end(), 1), 0);
}

TEST(CollisionPass, AnImpactZoneMovesWithItsClothInsteadOfStopping) {
  // Two sheets 3 mm apart move 1 cm along x together, while the upper
  // one's middle is thrown 6 mm down through the lower one. With no
  // rounds of pair corrections, impact zones alone resolve it: no
  // crossing, nothing put back, and every vertex still moved along x.
  std::vector<Cloth> cloths;
  cloths.emplace_back(grid(V3(0, 0, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 10, 10), Material{}, ClothOptions("inner", 0));
  cloths.emplace_back(grid(V3(0, 0.003, 0), V3(0.2, 0, 0), V3(0, 0, 0.2), 10, 10), Material{},
                      ClothOptions("outer", 1));
  std::vector<Cloth::State> states;
  for (const Cloth& c : cloths) states.push_back(c.state());
  std::vector<Cloth::State*> ptr;
  std::vector<Vec3s> push;
  std::vector<std::vector<std::uint8_t>> back;
  for (std::size_t c = 0; c < states.size(); ++c) {
    Cloth::State& s = states[c];
    ptr.push_back(&s);
    s.x_start = s.x;
    for (Vec3& p : s.x) {
      p.x() += 0.01;
      const bool middle = std::abs(p.x() - 0.11) < 0.045 && std::abs(p.z() - 0.1) < 0.045;
      if (c == 1 && middle) p.y() -= 0.006;
    }
    push.emplace_back(s.x.size(), Vec3::Zero());
    back.emplace_back(s.x.size(), 0);
  }
  detail::CollisionPass pass;
  const detail::CollisionPassStats st = pass.run(cloths, ptr, {}, 5e-4, 0, push, back);
  std::vector<Vec3s> now;
  for (auto& s : states) now.push_back(s.x);
  EXPECT_EQ(cloth_crossings(cloths, now), 0);
  EXPECT_GT(st.pairs, 0);
  EXPECT_GT(st.zoned, 0);
  EXPECT_EQ(st.reverted, 0);
  for (const auto& s : states)
    for (std::size_t i = 0; i < s.x.size(); ++i) EXPECT_GT(s.x[i].x() - s.x_start[i].x(), 0.005) << i;
}

SolverConfig pass_config(int substeps) {
  SolverConfig c;
  c.substeps = substeps;
  c.gravity = {0, 0, 0};
  c.air_damping = 0;
  c.max_speed = 0;
  c.collision_pass = true;
  return c;
}

std::vector<Vec3s> positions_of(const Solver& s) {
  std::vector<Vec3s> out;
  for (int c = 0; c < s.num_cloths(); ++c) out.push_back(s.cloth(c).state().x);
  return out;
}

std::vector<Cloth> cloths_of(const Solver& s) {
  std::vector<Cloth> out;
  for (int c = 0; c < s.num_cloths(); ++c) out.push_back(s.cloth(c));
  return out;
}

TEST(CollisionPass, SheetsDrivenThroughEachOtherAtSpeedStayApart) {
  // Two sheets of the same layer (no proximity contact between them at
  // all): only the pass stands between them. The upper one, tilted, is
  // thrown down through the lower one, one substep per frame.
  const auto run = [](bool pass, float speed, int frames) {
    SolverConfig config = pass_config(1);
    config.collision_pass = pass;
    Solver solver(config);
    solver.add_cloth(Cloth(grid(V3(0, 0, 0), V3(0, 0, 0.3), V3(0.3, 0, 0), 12, 12), Material{}, ClothOptions("a", 0)));
    solver.add_cloth(
        Cloth(grid(V3(0.01, 0.01, 0.01), V3(0, 0.02, 0.3), V3(0.3, 0, 0), 11, 11), Material{}, ClothOptions("b", 0)));
    geometry::Points v = solver.cloth(1).velocities();
    v.col(1).setConstant(-speed);
    solver.cloth(1).set_velocities(v);
    const std::vector<Cloth> cloths = cloths_of(solver);
    long worst = 0;
    for (int f = 0; f < frames; ++f) {
      solver.step();
      worst = std::max(worst, cloth_crossings(cloths, positions_of(solver)));
    }
    const std::vector<Vec3s> x = positions_of(solver);
    double mean_a = 0, mean_b = 0;
    for (const Vec3& p : x[0]) mean_a += p.y() / x[0].size();
    for (const Vec3& p : x[1]) mean_b += p.y() / x[1].size();
    return std::make_tuple(worst, mean_b - mean_a, solver.timings().pass_pairs);
  };
  // 0.6 m/s: 2 cm in the one substep of a frame, which ends crossed
  // without the pass.
  EXPECT_GT(std::get<0>(run(false, 0.6f, 1)), 0);
  const auto slow = run(true, 0.6f, 10);
  EXPECT_EQ(std::get<0>(slow), 0);
  EXPECT_GT(std::get<1>(slow), 0.0);  // b stays on top of a
  EXPECT_GT(std::get<2>(slow), 0);
  // 20 m/s: 67 cm in one substep, far past the lower sheet without the pass.
  const auto fast = run(true, 20.0f, 2);
  EXPECT_EQ(std::get<0>(fast), 0);
  EXPECT_GT(std::get<1>(fast), 0.0);
  EXPECT_LT(std::get<1>(run(false, 20.0f, 1)), 0.0);
}

TEST(CollisionPass, TwoLayersPinchedBetweenTwoPlatesKeepTheirOrder) {
  // Two plates (the body: two square sheets facing each other, 4 cm apart)
  // close to 2 mm within a few frames, two layers of cloth between them.
  const auto plates = [](double gap) {
    // Outward normals face the gap: up for the lower plate, down for the upper.
    geometry::TriMesh lower = grid(V3(-0.05, -gap / 2, -0.05), V3(0, 0, 0.3), V3(0.3, 0, 0), 6, 6);
    geometry::TriMesh upper = grid(V3(-0.05, gap / 2, -0.05), V3(0.3, 0, 0), V3(0, 0, 0.3), 6, 6);
    geometry::TriMesh both = geometry::concatenate({lower, upper});
    return both;
  };
  Solver solver(pass_config(4));
  solver.add_cloth(
      Cloth(grid(V3(0, -0.004, 0), V3(0, 0, 0.2), V3(0.2, 0, 0), 10, 10), Material{}, ClothOptions("inner", 0)));
  solver.add_cloth(
      Cloth(grid(V3(0, 0.004, 0), V3(0, 0, 0.2), V3(0.2, 0, 0), 10, 10), Material{}, ClothOptions("outer", 1)));
  solver.set_body(plates(0.04));
  const std::vector<Cloth> cloths = cloths_of(solver);
  for (int f = 1; f <= 8; ++f) {
    const double gap = std::max(0.002, 0.04 - 0.006 * f);
    solver.step(plates(gap).vertices);
    const std::vector<Vec3s> x = positions_of(solver);
    ASSERT_EQ(cloth_crossings(cloths, x), 0) << "frame " << f;
    // The outer layer is still above the inner one at the centre.
    EXPECT_GT(x[1][60].y(), x[0][60].y()) << "frame " << f;
    // Where the plates press the layers from both sides the plates yield:
    // the cloth is not torn apart by pushes out of one plate into the other.
    for (int c = 0; c < 2; ++c) {
      const Cloth& cloth = solver.cloth(c);
      EXPECT_LT(max_edge_stretch(cloth.positions(), cloth.edges(), cloth.rest_lengths()), 0.15)
          << "frame " << f << " cloth " << c;
    }
  }
}

TEST(CollisionPass, AThinStripCrumpledOntoItselfNeverCrossesItself) {
  // A collar-like strip (40 x 1 quads, self-contact) whose ends are driven
  // towards each other so that it buckles into folds.
  Solver solver(pass_config(5));
  solver.add_cloth(
      Cloth(grid(V3(0, 0, 0), V3(0.4, 0, 0), V3(0, 0.02, 0), 40, 1), Material{}, ClothOptions("rim", 1, true)));
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.5f, 1.5f);
  const std::vector<Cloth> cloths = cloths_of(solver);
  for (int f = 0; f < 20; ++f) {
    geometry::Points v = solver.cloth(0).velocities();
    for (Eigen::Index i = 0; i < v.rows(); ++i) {
      v(i, 0) += (solver.cloth(0).state().x[i].x() < 0.2 ? 1.0f : -1.0f) + u(rng);
      v(i, 1) += u(rng);
      v(i, 2) += u(rng);
    }
    solver.cloth(0).set_velocities(v);
    solver.step();
    ASSERT_EQ(cloth_crossings(cloths, positions_of(solver)), 0) << "frame " << f;
  }
}

TEST(CollisionPass, SameInputsGiveTheSameFrames) {
  const auto run = [] {
    Solver solver(pass_config(2));
    solver.add_cloth(Cloth(grid(V3(0, 0, 0), V3(0, 0, 0.2), V3(0.2, 0, 0), 8, 8), Material{}, ClothOptions("a", 0)));
    solver.add_cloth(
        Cloth(grid(V3(0, 0.01, 0), V3(0, 0, 0.2), V3(0.2, 0, 0), 8, 8), Material{}, ClothOptions("b", 1, true)));
    geometry::Points v = solver.cloth(1).velocities();
    v.col(1).setConstant(-5.0f);
    solver.cloth(1).set_velocities(v);
    for (int f = 0; f < 5; ++f) solver.step();
    return positions_of(solver);
  };
  const std::vector<Vec3s> a = run(), b = run();
  for (std::size_t c = 0; c < a.size(); ++c)
    for (std::size_t i = 0; i < a[c].size(); ++i) ASSERT_EQ(a[c][i], b[c][i]);
}

}  // namespace
}  // namespace layers::sim
