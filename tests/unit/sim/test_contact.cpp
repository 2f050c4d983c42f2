// Contact: friction on an incline, a sheet dropped on a sphere, a fast box
// through a sheet, two layers on a box, self-contact of a folded strip.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include <Eigen/Geometry>

#include "scenes.h"

namespace layers::sim {
namespace {

using geometry::Points;
using test::V3;

Points transformed(const Points& p, const Eigen::Matrix3d& r, const V3& t) {
  Points out(p.rows(), 3);
  for (Eigen::Index i = 0; i < p.rows(); ++i)
    out.row(i) = (r * p.row(i).cast<double>().transpose() + t).cast<float>().transpose();
  return out;
}

// Signed distance to a box of half extents `half` rounded by r, centred at c.
double rounded_box_distance(const V3& p, const V3& c, const V3& half, double r) {
  const V3 inner = half - V3::Constant(r);
  const V3 q = (p - c).cwiseAbs() - inner;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0) - r;
}

TEST(Contact, HigherFrictionSlidesLess) {
  // A slab tilted by 30 degrees (tan 30 = 0.58): friction 40 (mu 0.4) slides,
  // friction 80 (mu 0.8) holds.
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(-30.0 * 3.14159265358979 / 180, V3::UnitZ()).toRotationMatrix();
  const V3 downhill = tilt * V3(1, 0, 0);
  double slid[2];
  for (int k = 0; k < 2; ++k) {
    Solver s;
    geometry::TriMesh slab = test::rounded_box(V3(0, 0, 0), V3(0.5, 0.03, 0.25), 0.02, 0.025);
    slab.vertices = transformed(slab.vertices, tilt, V3(0, 0.5, 0));
    s.set_body(slab);
    geometry::TriMesh sheet = test::grid(V3(-0.35, 0.036, 0.1), V3(0.2, 0, 0), V3(0, 0, -0.2), 10, 10);
    sheet.vertices = transformed(sheet.vertices, tilt, V3(0, 0.5, 0));
    GarmentAttributes a;
    a.friction = k == 0 ? 40 : 80;
    s.add_cloth(Cloth(sheet, to_material(a)));
    const V3 start = test::centroid(s.cloth(0).positions());
    for (int f = 0; f < 15; ++f) s.step();
    slid[k] = (test::centroid(s.cloth(0).positions()) - start).dot(downhill);
    std::printf("[sim] sheet on a 30 degree slope, friction %.0f: slid %.1f mm in 0.5 s\n", a.friction, 1000 * slid[k]);
  }
  EXPECT_GT(slid[0], 0.05);  // a = g (sin 30 - 0.4 cos 30) = 1.5 m/s^2: ~19 cm
  EXPECT_LT(slid[1], 0.01);  // static friction holds
  EXPECT_GT(slid[0], slid[1]);
}

TEST(Contact, BodyEdgesKeepACoarseSheetOnTopOfARidge) {
  // A finely tessellated box turned 45 degrees about x: its top edge is a
  // straight ridge along x at y = 0. A coarse sheet (10 cm cells, its
  // vertex rows at z = -5 and +5 cm) falls onto it. Vertex-face contact
  // holds the vertices on the two roof slopes, and the ridge pokes up
  // through the faces between them; body edge contact, or the collision
  // pass alone, keeps the sheet's edges across the ridge above it, so no
  // face is crossed.
  const double half = 0.1;
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(3.14159265358979 / 4, V3::UnitX()).toRotationMatrix();
  const geometry::TriMesh block = test::box(V3::Zero(), V3(0.3, half, half), 0.02);
  const geometry::TriMesh ridge{transformed(block.vertices, turn, V3(0, -half * std::sqrt(2.0), 0)), block.faces};
  double crossing[3], worst[3];
  for (int k = 0; k < 3; ++k) {
    SolverConfig c;
    c.body_edge_thickness = k == 1 ? 0.002 : 0.0;
    c.collision_pass = k == 2;
    Solver s(c);
    s.set_body(ridge);
    s.add_cloth(Cloth(test::grid(V3(-0.15, 0.01, -0.05), V3(0.3, 0, 0), V3(0, 0, 0.1), 3, 1), to_material({})));
    worst[k] = 0;
    for (int f = 0; f < 30; ++f) {
      s.step();
      worst[k] = std::max(worst[k], measure_frame(s).h_crossing);
    }
    crossing[k] = measure_frame(s).h_crossing;
    EXPECT_TRUE(s.cloth(0).positions().allFinite());
  }
  std::printf(
      "[sim] coarse sheet on a ridge: H-crossing %.1f%% with vertex-face contact only, %.1f%% with body edges (worst "
      "%.1f%%), %.1f%% with the collision pass (worst %.1f%%)\n",
      100 * crossing[0], 100 * crossing[1], 100 * worst[1], 100 * crossing[2], 100 * worst[2]);
  EXPECT_GT(crossing[0], 0.5);  // the scene does test something
  EXPECT_EQ(worst[1], 0.0);
  EXPECT_EQ(worst[2], 0.0);
}

TEST(Contact, SheetDroppedOnASphereStaysOutside) {
  Solver s;
  const V3 centre(0, 0.5, 0);
  const double radius = 0.15;
  s.set_body(test::icosphere(centre, radius, 4));
  s.add_cloth(Cloth(test::grid(V3(-0.3, 0.7, 0.3), V3(0.6, 0, 0), V3(0, 0, -0.6), 24, 24), to_material({})));
  SequenceMeasures measures;
  int inside = 0;
  for (int f = 0; f < 60; ++f) {
    s.step();
    measures.add(measure_frame(s));
    const Points p = s.cloth(0).positions();
    for (Eigen::Index i = 0; i < p.rows(); ++i)
      inside += (p.row(i).cast<double>().transpose() - centre).norm() < radius;
  }
  const FrameMeasures last = measure_frame(s);
  std::printf("[sim] sheet on a sphere after 2 s: H-penetration %.3f%% (mean over frames %.3f%%), max stretch %.1f%%\n",
              100 * last.h_penetration, 100 * measures.mean_h_penetration(), 100 * measures.max_stretch());
  EXPECT_EQ(last.h_penetration, 0.0);
  EXPECT_EQ(inside, 0);
  EXPECT_LT(measures.max_stretch(), 0.10);
}

// Counts sheet vertices inside a box moving 0.5 m per frame through the
// sheet, over all frames; returns the final centroid z of the sheet.
double fast_box(int substeps, int& inside) {
  SolverConfig c;
  c.substeps = substeps;
  Solver s(c);
  const V3 half(0.1, 0.1, 0.1);
  const double r = 0.02;
  const geometry::TriMesh box = test::rounded_box(V3(0, 0, 0), half, r, 0.015);
  const auto at = [&](int frame) { return V3(0, 0.5, -0.6 + 0.5 * frame); };
  s.set_body({transformed(box.vertices, Eigen::Matrix3d::Identity(), at(0)), box.faces});
  s.add_cloth(Cloth(test::grid(V3(-0.2, 0.7, 0), V3(0.4, 0, 0), V3(0, -0.4, 0), 16, 16), to_material({})));
  inside = 0;
  for (int f = 1; f <= 4; ++f) {
    s.step(transformed(box.vertices, Eigen::Matrix3d::Identity(), at(f)));
    const Points p = s.cloth(0).positions();
    for (Eigen::Index i = 0; i < p.rows(); ++i) {
      inside += rounded_box_distance(p.row(i).cast<double>().transpose(), at(f), half, r) < -0.001;
    }
  }
  return test::centroid(s.cloth(0).positions()).z() - at(4).z();
}

TEST(Contact, FastBoxDoesNotTunnel) {
  int inside = 0;
  const double ahead = fast_box(SolverConfig{}.substeps, inside);
  int inside_one = 0;
  const double ahead_one = fast_box(1, inside_one);
  std::printf(
      "[sim] box at 15 m/s (0.5 m per frame) through a sheet: %d vertex-frames inside, sheet centroid %.0f mm "
      "from the box centre (front face at +100 mm); with 1 substep: %d inside, %.0f mm\n",
      inside, 1000 * ahead, inside_one, 1000 * ahead_one);
  EXPECT_EQ(inside, 0);
  EXPECT_GT(ahead, 0.05);  // carried in front of the box, not left behind it
}

TEST(Contact, TwoLayersOnABoxStayLayered) {
  Solver s;
  s.set_body(test::rounded_box(V3(0, 0.5, 0), V3(0.3, 0.1, 0.3), 0.03, 0.025));
  s.add_cloth(Cloth(test::grid(V3(-0.15, 0.61, 0.15), V3(0.3, 0, 0), V3(0, 0, -0.3), 12, 12), to_material({}),
                    ClothOptions("inner", 0)));
  s.add_cloth(Cloth(test::grid(V3(-0.12, 0.64, 0.12), V3(0.24, 0, 0), V3(0, 0, -0.24), 12, 12), to_material({}),
                    ClothOptions("outer", 1)));
  SequenceMeasures measures;
  for (int f = 0; f < 45; ++f) {
    s.step();
    measures.add(measure_frame(s));
  }
  const double gap = test::centroid(s.cloth(1).positions()).y() - test::centroid(s.cloth(0).positions()).y();
  std::printf(
      "[sim] outer sheet dropped on an inner sheet on a box: L-penetration %.3f%% (mean over frames), "
      "layer gap %.1f mm (thickness %.1f mm)\n",
      100 * measures.mean_l_penetration(), 1000 * gap, 1000 * s.config().layer_thickness);
  EXPECT_LT(measures.mean_l_penetration(), 0.005);
  EXPECT_EQ(measures.mean_h_penetration(), 0.0);
  EXPECT_GT(gap, 0.5 * s.config().layer_thickness);
  EXPECT_LT(gap, 2.5 * s.config().layer_thickness);
}

// A strip folded over itself (a half-circle fold of radius r) lying on a
// box: with self-contact the top half stays on the bottom one.
double folded_strip_gap(bool self_contact) {
  Solver s;
  s.set_body(test::rounded_box(V3(0, 0.5, 0), V3(0.3, 0.1, 0.3), 0.03, 0.025));
  const double length = 0.5, width = 0.2, r = 0.015, y0 = 0.608;
  const geometry::TriMesh rest = test::grid(V3(-width / 2, 0, 0), V3(width, 0, 0), V3(0, 0, length), 10, 25);
  ClothOptions o;
  o.self_contact = self_contact;
  Cloth cloth(rest, to_material({}), o);
  const double pi = 3.14159265358979323846, s1 = length / 2 - pi * r / 2, s2 = length / 2 + pi * r / 2;
  Points folded(rest.num_vertices(), 3);
  for (int i = 0; i < rest.num_vertices(); ++i) {
    const double x = rest.vertices(i, 0), t = rest.vertices(i, 2);
    V3 p;
    if (t <= s1)
      p = V3(x, y0, t - 0.15);
    else if (t >= s2)
      p = V3(x, y0 + 2 * r, s1 - (t - s2) - 0.15);
    else
      p = V3(x, y0 + r - r * std::cos((t - s1) / r), s1 + r * std::sin((t - s1) / r) - 0.15);
    folded.row(i) = p.cast<float>().transpose();
  }
  cloth.set_positions(folded);
  s.add_cloth(std::move(cloth));
  for (int f = 0; f < 45; ++f) s.step();
  // Mean height of the flat parts of the top and the bottom half.
  const Points p = s.cloth(0).positions();
  double top = 0, bottom = 0;
  int nt = 0, nb = 0;
  for (int i = 0; i < rest.num_vertices(); ++i) {
    const double t = rest.vertices(i, 2);
    if (t < s1 - 0.05) {
      bottom += p(i, 1);
      ++nb;
    }
    if (t > s2 + 0.05) {
      top += p(i, 1);
      ++nt;
    }
  }
  return top / nt - bottom / nb;
}

TEST(Contact, SelfContactKeepsAFoldApart) {
  const double with = folded_strip_gap(true), without = folded_strip_gap(false);
  std::printf(
      "[sim] strip folded on itself: top half %.1f mm above the bottom half with self-contact, %.1f mm "
      "without\n",
      1000 * with, 1000 * without);
  EXPECT_GT(with, 0.5 * SolverConfig{}.self_thickness);
  EXPECT_LT(without, 0.5 * SolverConfig{}.self_thickness);
}

}  // namespace
}  // namespace layers::sim
