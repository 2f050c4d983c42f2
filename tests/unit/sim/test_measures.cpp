// Validation measures: penetration rates, stretch, non-finite values, the
// per-sequence verdict and measure_frame() on a solver.
#include <gtest/gtest.h>

#include <algorithm>

#include <cmath>
#include <cstdio>
#include <limits>
#include <set>

#include "scenes.h"

namespace layers::sim {
namespace {

using geometry::Points;
using test::V3;

Points rows(std::initializer_list<V3> list) {
  Points p(static_cast<Eigen::Index>(list.size()), 3);
  Eigen::Index i = 0;
  for (const V3& v : list) p.row(i++) = v.cast<float>().transpose();
  return p;
}

// A unit square grid at height y, normals up.
geometry::TriMesh floor_at(double y) { return test::grid(V3(0, y, 1), V3(1, 0, 0), V3(0, 0, -1), 10, 10); }

TEST(Measures, PenetrationRates) {
  const geometry::TriMesh body = floor_at(0);
  EXPECT_DOUBLE_EQ(h_penetration_rate(
                       {rows({{0.3, 0.01, 0.3}, {0.5, -0.02, 0.5}}), rows({{0.7, 0.2, 0.1}, {0.2, -0.1, 0.8}})}, body),
                   0.5);
  const geometry::TriMesh inner = floor_at(0.1);
  EXPECT_DOUBLE_EQ(
      l_penetration_rate({rows({{0.5, 0.12, 0.5}, {0.2, 0.08, 0.3}, {0.6, 0.15, 0.6}, {0.9, 0.11, 0.9}})}, {inner}),
      0.25);
  EXPECT_DOUBLE_EQ(l_penetration_rate({rows({{0.5, 0.12, 0.5}})}, {}), 0.0);
  EXPECT_DOUBLE_EQ(penetration_rate(Points(0, 3), geometry::Surface::from_mesh(body)), 0.0);
}

TEST(Measures, LPenetrationIgnoresAnOverhangPastTheInnerHem) {
  // Inner sheet: vertical, facing +z, from y = 0.5 to 1.0. Outer sheet in
  // front of it (z = 0.01) from y = 0.2 to 1.0; below the inner hem it
  // swings inwards (z = -0.01) without crossing anything.
  const geometry::TriMesh inner = test::grid(V3(0, 0.5, 0), V3(1, 0, 0), V3(0, 0.5, 0), 10, 5);
  geometry::TriMesh outer = test::grid(V3(0, 0.2, 0.01), V3(1, 0, 0), V3(0, 0.8, 0), 10, 16);
  for (Eigen::Index i = 0; i < outer.vertices.rows(); ++i) {
    if (outer.vertices(i, 1) < 0.49f) outer.vertices(i, 2) = -0.01f;
  }
  const Eigen::Index n = outer.vertices.rows();
  // The old nearest-vertex test counts the whole overhang row by row.
  const double nearest_vertex = penetration_rate(outer.vertices, geometry::Surface::from_mesh(inner));
  EXPECT_GT(nearest_vertex, 0.3);
  EXPECT_DOUBLE_EQ(l_penetration_rate({outer.vertices}, {inner}), 0.0);
  // A vertex pushed through the inner sheet above its hem is counted.
  const Eigen::Index through = 11 * 11 + 4;  // row y = 0.75, x = 0.4
  ASSERT_NEAR(outer.vertices(through, 1), 0.75f, 1e-6f);
  outer.vertices(through, 2) = -0.005f;
  EXPECT_DOUBLE_EQ(l_penetration_rate({outer.vertices}, {inner}), 1.0 / static_cast<double>(n));
  // So is one just under the hem row, directly below the inner surface.
  outer.vertices(through, 2) = 0.01f;
  const Eigen::Index under_hem = 6 * 11 + 7;  // row y = 0.5, x = 0.7
  ASSERT_NEAR(outer.vertices(under_hem, 1), 0.5f, 1e-6f);
  outer.vertices(under_hem, 2) = -0.005f;
  EXPECT_DOUBLE_EQ(l_penetration_rate({outer.vertices}, {inner}), 1.0 / static_cast<double>(n));
}

TEST(Measures, LPenetrationOnlyWithinReachOfTheInnerLayer) {
  // A jacket sleeve over a bare forearm: the nearest inner point is far
  // away (here 5 cm above the point) and says nothing about being inside.
  const geometry::TriMesh inner = floor_at(0.1);
  const Points outer = rows({{0.5, 0.05, 0.5}, {0.3, 0.09, 0.3}, {0.6, 0.12, 0.6}});
  EXPECT_DOUBLE_EQ(l_penetration_rate({outer}, {inner}), 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(l_penetration_rate({outer}, {inner}, 0.03), 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(l_penetration_rate({outer}, {inner}, 0.005), 0.0);
}

TEST(Measures, LPenetrationTestsTheInnerGarmentsAsOneLayer) {
  // A skirt whose waistband (at y 0.1, facing down as if folded under) is
  // covered by a t-shirt hem 1 cm above it; a jacket vertex 5 mm above the
  // t-shirt is outside the inner layer, though behind the skirt band alone.
  const geometry::TriMesh skirt = test::grid(V3(0, 0.1, 0), V3(1, 0, 0), V3(0, 0, 1), 10, 10);  // normals down
  const geometry::TriMesh tshirt = floor_at(0.11);
  const Points jacket = rows({{0.55, 0.115, 0.45}});
  EXPECT_DOUBLE_EQ(l_penetration_rate({jacket}, {skirt}), 1.0);
  EXPECT_DOUBLE_EQ(l_penetration_rate({jacket}, {skirt, tshirt}), 0.0);
  EXPECT_DOUBLE_EQ(l_penetration_rate({rows({{0.55, 0.105, 0.45}})}, {skirt, tshirt}), 1.0);
}

TEST(Measures, LPenetrationIgnoresAFoldOfTheInnerGarment) {
  // Body: the floor (normals up). Inner: a sheet at y = 0.02 and, above it,
  // the underside of a fold (a flap at y = 0.04 facing down). An outer
  // vertex just above the flap is behind it by the sign alone, but nothing
  // of the inner layer covers it along the body normal; one under the
  // sheet is covered (the ray up leaves the sheet through its back).
  const geometry::TriMesh body = floor_at(0);
  const geometry::TriMesh sheet = floor_at(0.02);
  const geometry::TriMesh flap = test::grid(V3(0.4, 0.04, 0.4), V3(0.2, 0, 0), V3(0, 0, 0.2), 4, 4);
  const geometry::Surface normals = geometry::Surface::from_mesh(body);
  const Points above_flap = rows({{0.51, 0.045, 0.49}});
  EXPECT_DOUBLE_EQ(l_penetration_rate({above_flap}, {sheet, flap}, 0.03), 1.0);
  EXPECT_DOUBLE_EQ(l_penetration_rate({above_flap}, {sheet, flap}, 0.03, &normals), 0.0);
  const Points under_sheet = rows({{0.21, 0.015, 0.73}});
  EXPECT_DOUBLE_EQ(l_penetration_rate({under_sheet}, {sheet, flap}, 0.03, &normals), 1.0);
}

TEST(Measures, StretchAndNonFinite) {
  const Points rest = rows({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}});
  geometry::Edges edges(3, 2);
  edges << 0, 1, 0, 2, 1, 2;
  Eigen::VectorXd l0(3);
  l0 << 1, 1, std::sqrt(2.0);
  EXPECT_NEAR(max_edge_stretch(rest, edges, l0), 0.0, 1e-7);
  const Points stretched = rows({{0, 0, 0}, {1.1, 0, 0}, {0, 0.5, 0}});  // +10% and -50%
  EXPECT_NEAR(max_edge_stretch(stretched, edges, l0), 0.1, 1e-6);
  Points bad = rest;
  bad(1, 2) = std::numeric_limits<float>::quiet_NaN();
  bad(2, 0) = std::numeric_limits<float>::infinity();
  EXPECT_EQ(count_nonfinite(bad), 2);
  EXPECT_TRUE(std::isnan(max_edge_stretch(bad, edges, l0)));
}

TEST(Measures, SequenceVerdict) {
  SequenceMeasures good;
  good.add({0.001, 0.002, 0.05, 0});
  good.add({0.003, 0.004, 0.07, 0});
  EXPECT_EQ(good.frames(), 2);
  EXPECT_NEAR(good.mean_h_penetration(), 0.002, 1e-12);
  EXPECT_NEAR(good.mean_l_penetration(), 0.003, 1e-12);
  EXPECT_DOUBLE_EQ(good.max_stretch(), 0.07);
  EXPECT_TRUE(good.violations(ValidationConfig{}).empty());

  SequenceMeasures bad = good;
  bad.add({0.03, 0.0, 0.2, 0});
  const double nan = std::numeric_limits<double>::quiet_NaN();
  bad.add({nan, nan, nan, 5});
  const auto v = bad.violations(ValidationConfig{});
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0], "5 non-finite coordinates");
  EXPECT_EQ(v[1], "mean H-penetration 1.13% exceeds 0.50%");
  EXPECT_EQ(v[2], "maximum edge stretch 20.00% exceeds 10.00%");
}

TEST(Measures, CrossingsOfAFrame) {
  // Body: the floor. Inner sheet 2 cm over it; the outer sheet 4 cm over it,
  // except one vertex pushed below the inner sheet (its six faces pass
  // through the inner layer) and, in a second frame, below the floor too.
  const geometry::TriMesh body = floor_at(0);
  const geometry::TriMesh inner = test::grid(V3(0.11, 0.02, 0.87), V3(0.77, 0, 0), V3(0, 0, -0.73), 8, 8);
  geometry::TriMesh outer = test::grid(V3(0.13, 0.04, 0.83), V3(0.71, 0, 0), V3(0, 0, -0.69), 5, 5);
  // The vertices on faces around outer vertex 14 (an interior one).
  std::set<int> ring;
  for (int f = 0; f < outer.num_faces(); ++f)
    if ((outer.faces.row(f).array() == 14).any())
      for (int k = 0; k < 3; ++k) ring.insert(outer.faces(f, k));
  const double n = static_cast<double>(ring.size());
  const auto garments = [&](const geometry::TriMesh& o) {
    return std::vector<MeasuredGarment>{{inner.vertices, inner.faces, geometry::Edges(0, 2), Eigen::VectorXd(0), false},
                                        {o.vertices, o.faces, geometry::Edges(0, 2), Eigen::VectorXd(0), true}};
  };
  FrameMeasures clean = measure_frame(body, garments(outer));
  EXPECT_EQ(clean.h_crossing, 0.0);
  EXPECT_EQ(clean.l_crossing, 0.0);
  EXPECT_EQ(clean.l_crossing_pairs, 0);

  outer.vertices(14, 1) = 0.01f;  // an interior vertex, between floor and inner sheet
  const FrameMeasures through_inner = measure_frame(body, garments(outer));
  EXPECT_EQ(through_inner.h_crossing, 0.0);
  EXPECT_GT(through_inner.l_crossing_pairs, 0);
  EXPECT_DOUBLE_EQ(through_inner.l_crossing, n / 36.0);

  outer.vertices(14, 1) = -0.01f;  // through the floor as well
  const FrameMeasures through_body = measure_frame(body, garments(outer));
  EXPECT_GT(through_body.h_crossing_pairs, 0);
  EXPECT_DOUBLE_EQ(through_body.h_crossing, n / (81.0 + 36.0));
  // The floor does not cross itself: the H-crossing clear of the body's own
  // crossings is the whole H-crossing; without body_self neither is measured.
  EXPECT_EQ(through_body.body_self_crossing, 0.0);
  EXPECT_DOUBLE_EQ(through_body.h_crossing_clear, through_body.h_crossing);
  const FrameMeasures unasked = measure_frame(body, garments(outer), ValidationConfig{}.l_reach, false);
  EXPECT_TRUE(std::isnan(unasked.body_self_crossing));
  EXPECT_TRUE(std::isnan(unasked.h_crossing_clear));
  EXPECT_DOUBLE_EQ(unasked.h_crossing, through_body.h_crossing);

  // A second body part 12 mm over the floor, away from the crossing: a
  // pinch zone, and the crossing is outside it; over the crossing: inside.
  const auto with_plate = [&](double x, double z) {
    // The floor and the plate with 1 cm edges (pinch zones are found
    // between vertices).
    return geometry::concatenate({test::grid(V3(0, 0, 1), V3(1, 0, 0), V3(0, 0, -1), 100, 100),
                                  test::grid(V3(x, 0.012, z), V3(0.3, 0, 0), V3(0, 0, -0.3), 30, 30)});
  };
  const FrameMeasures apart = measure_frame(with_plate(0.7, 0.3), garments(outer));
  EXPECT_GT(apart.body_pinch, 0.0);
  EXPECT_DOUBLE_EQ(apart.h_crossing_clear, apart.h_crossing);
  EXPECT_EQ(apart.h_crossing_pinch, 0.0);
  const FrameMeasures over = measure_frame(with_plate(0.3, 0.7), garments(outer));
  EXPECT_GT(over.h_crossing, 0.0);
  EXPECT_EQ(over.h_crossing_clear, 0.0);
  EXPECT_DOUBLE_EQ(over.h_crossing_pinch, over.h_crossing);
  // The clear part has its own threshold.
  SequenceMeasures seen;
  seen.add(apart);
  ValidationConfig strict;
  strict.max_h_crossing_clear = 0;
  const std::vector<std::string> said = seen.violations(strict);
  EXPECT_TRUE(std::any_of(said.begin(), said.end(), [](const std::string& s) {
    return s.find("H-crossing outside pinch zones") != std::string::npos;
  }));
  SequenceMeasures pinched_only;
  pinched_only.add(over);
  for (const std::string& p : pinched_only.violations(strict)) EXPECT_EQ(p.find("outside pinch"), std::string::npos);

  SequenceMeasures seq;
  seq.add(clean);
  seq.add(through_body);
  EXPECT_DOUBLE_EQ(seq.max_l_crossing(), n / 36.0);
  EXPECT_DOUBLE_EQ(seq.mean_l_crossing(), n / 72.0);
  ValidationConfig limits;
  limits.max_h_crossing = 0.001;
  limits.max_l_crossing = 0.001;
  // (The pushed vertex is also behind both surfaces: mean H- and
  // L-penetration may object too.)
  const auto v = seq.violations(limits);
  const auto has = [&](const std::string& text) {
    for (const std::string& line : v)
      if (line == text) return true;
    return false;
  };
  char h[64], l[64];
  std::snprintf(h, sizeof h, "H-crossing %.2f%% in a frame exceeds 0.10%%", 100 * n / 117.0);
  std::snprintf(l, sizeof l, "L-crossing %.2f%% in a frame exceeds 0.10%%", 100 * n / 36.0);
  EXPECT_TRUE(has(h)) << h;
  EXPECT_TRUE(has(l)) << l;
  EXPECT_TRUE(SequenceMeasures().violations(limits).empty());
}

TEST(Measures, ClothCrossingsCountEveryPairOfGarmentsAndSelfWhereUsed) {
  // Two sheets of the same layer (a t-shirt and trousers, say), the second
  // tilted through the first; a third sheet folded through itself.
  const geometry::TriMesh a = test::grid(V3(0, 0, 0), V3(0, 0, 0.3), V3(0.3, 0, 0), 6, 6);
  geometry::TriMesh b = test::grid(V3(0.02, 0.01, 0.02), V3(0, 0, 0.25), V3(0.25, 0, 0), 5, 5);
  const auto sheet = [](const geometry::TriMesh& m, bool self) {
    return MeasuredGarment{m.vertices, m.faces, geometry::Edges(0, 2), Eigen::VectorXd(0), false, self};
  };
  EXPECT_EQ(cloth_crossings({sheet(a, false), sheet(b, false)}), 0);
  b.vertices(14, 1) = -0.02f;  // an interior vertex pushed through the other sheet
  const std::int64_t between = cloth_crossings({sheet(a, false), sheet(b, false)});
  EXPECT_GT(between, 0);
  // A sheet whose last row of faces is folded back down through its first
  // row: counted only when the garment has self-contact.
  geometry::TriMesh folded = test::grid(V3(0, 0, 0), V3(0, 0, 0.3), V3(0.3, 0, 0), 6, 6);
  for (int i = 0; i < folded.num_vertices(); ++i) {
    if (folded.vertices(i, 2) > 0.27f) {
      folded.vertices(i, 2) = 0.02f;
      folded.vertices(i, 1) = 0.03f;
    }
    if (folded.vertices(i, 2) > 0.22f && folded.vertices(i, 2) < 0.27f) folded.vertices(i, 1) = -0.03f;
  }
  EXPECT_EQ(cloth_crossings({sheet(folded, false)}), 0);
  EXPECT_GT(cloth_crossings({sheet(folded, true)}), 0);
  // The frame's count and the sequence's worst frame, against the rule.
  const FrameMeasures f = measure_frame(floor_at(-1), {sheet(a, false), sheet(b, false)});
  EXPECT_EQ(f.cloth_crossing_pairs, between);
  SequenceMeasures seq;
  seq.add(f);
  EXPECT_EQ(seq.max_cloth_crossings(), between);
  const auto v = seq.violations(ValidationConfig{});
  ASSERT_FALSE(v.empty());
  EXPECT_EQ(v.back(), std::to_string(between) + " crossing face pairs between garments in a frame exceed 0");
}

TEST(Measures, FrameOfASolverUsesTheTopLayerAsOuter) {
  Solver s;
  s.set_body(floor_at(0));
  s.add_cloth(
      Cloth(test::grid(V3(0.2, 0.05, 0.8), V3(0.6, 0, 0), V3(0, 0, -0.6), 6, 6), Material{}, ClothOptions("inner", 0)));
  // The outer sheet is placed below the inner one: every vertex is behind it.
  s.add_cloth(
      Cloth(test::grid(V3(0.2, 0.03, 0.8), V3(0.6, 0, 0), V3(0, 0, -0.6), 6, 6), Material{}, ClothOptions("outer", 1)));
  const FrameMeasures m = measure_frame(s);
  EXPECT_DOUBLE_EQ(m.h_penetration, 0.0);
  EXPECT_DOUBLE_EQ(m.l_penetration, 1.0);
  EXPECT_NEAR(m.max_stretch, 0.0, 1e-6);
  EXPECT_EQ(m.nonfinite, 0);
  // A single layer has no L-penetration.
  Solver one;
  one.add_cloth(Cloth(test::grid(V3(0, 1, 0), V3(0.3, 0, 0), V3(0, 0, 0.3), 3, 3), Material{}));
  EXPECT_DOUBLE_EQ(measure_frame(one).l_penetration, 0.0);
  EXPECT_DOUBLE_EQ(measure_frame(one).h_penetration, 0.0);
}

}  // namespace
}  // namespace layers::sim

namespace layers::sim {
namespace {

std::vector<std::string> rules(const std::vector<Violation>& v) {
  std::vector<std::string> out;
  for (const Violation& x : v) out.push_back(x.rule);
  return out;
}

// One frame's rules (clean windows): each limit by name, NaN measures
// breaking nothing but the non-finite rule, and a sequence's violations
// the same rules on its worst frame after the two means.
TEST(Measures, FrameViolationsNameEachBrokenRule) {
  ValidationConfig limits;
  limits.max_h_crossing = 0.01;
  limits.max_h_crossing_clear = 0.0;
  FrameMeasures f;
  EXPECT_TRUE(frame_violations(f, limits).empty());
  f.max_stretch = 0.11;
  f.cloth_crossing_pairs = 1;
  f.h_crossing = 0.02;
  f.h_crossing_clear = 0.001;
  EXPECT_EQ(rules(frame_violations(f, limits)),
            (std::vector<std::string>{"h_crossing", "h_crossing_clear", "cloth_crossings", "stretch"}));
  FrameMeasures lost;
  lost.nonfinite = 3;
  lost.h_penetration = lost.l_penetration = lost.max_stretch = std::nan("");
  lost.h_crossing = lost.l_crossing = lost.h_crossing_clear = std::nan("");
  EXPECT_EQ(rules(frame_violations(lost, limits)), std::vector<std::string>{"non_finite"});
  FrameMeasures unmeasured;  // pinch zones not measured in this frame
  unmeasured.h_crossing_clear = std::nan("");
  EXPECT_TRUE(frame_violations(unmeasured, limits).empty());

  SequenceMeasures seq;
  FrameMeasures good;
  good.body_self_crossing = 0;
  seq.add(good);
  f.body_self_crossing = 0;
  f.h_penetration = 0.9;  // breaks the mean too
  seq.add(f);
  EXPECT_EQ(rules(seq.broken(limits)), (std::vector<std::string>{"h_penetration", "h_crossing", "h_crossing_clear",
                                                                 "cloth_crossings", "stretch"}));
  EXPECT_EQ(seq.violations(limits).size(), 5u);
}

}  // namespace
}  // namespace layers::sim
