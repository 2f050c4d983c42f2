// A garment built folded over itself at an opening's corner is smoothed,
// its opening too once smoothing inside the opening alone has not
// parted it, until it no longer crosses itself; a garment that does not
// cross itself is left as it was.
#include <gtest/gtest.h>

#include <vector>

#include "layers/garment/garment_untangle.h"
#include "layers/geometry/intersect.h"

namespace layers::garment {
namespace {

std::int64_t self_pairs(const geometry::TriMesh& m) { return geometry::self_crossings(geometry::FaceTree(m)).pairs; }

// The 13 faces around the bottom corner of a fitted dress's back
// neckline (medium's scene 28 in the T-pose), in mm about the corner:
// vertices 0-3 lie on the neckline (2 is the corner of its flat bottom),
// and face (10, 2, 3) spans that corner, folded over the faces beside it.
geometry::TriMesh folded_neckline_corner() {
  geometry::TriMesh m;
  const float p[13][3] = {{-9.33f, 32.99f, 0.61f},   {-7.60f, 8.43f, 0.16f},   {-4.63f, -14.81f, -0.26f},
                          {20.00f, -14.81f, -0.23f}, {5.52f, -30.42f, 4.28f},  {-20.56f, -28.42f, 4.44f},
                          {19.40f, -20.58f, 2.37f},  {-4.22f, -18.25f, 2.30f}, {-32.58f, -11.92f, 2.25f},
                          {-17.07f, -3.36f, 0.72f},  {-9.97f, 0.71f, -0.02f},  {-30.69f, 16.54f, -0.10f},
                          {-17.46f, 19.94f, 0.01f}};
  m.vertices.resize(13, 3);
  for (int v = 0; v < 13; ++v) m.vertices.row(v) << 0.001f * p[v][0], 0.001f * p[v][1], 0.001f * p[v][2];
  m.faces.resize(13, 3);
  m.faces << 11, 10, 9, 8, 7, 5, 9, 7, 8, 9, 3, 7, 7, 6, 4, 12, 10, 11, 7, 4, 5, 7, 3, 6, 12, 2, 10, 10, 3, 9, 10, 2, 3,
      0, 1, 12, 12, 1, 2;
  return m;
}

TEST(GarmentUntangle, AFoldAtAnOpeningCornerIsRelaxedUntilNothingCrosses) {
  geometry::TriMesh m = folded_neckline_corner();
  ASSERT_GT(self_pairs(m), 0);  // the fixture is folded
  const std::vector<std::uint8_t> opening = {1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const geometry::Points before = m.vertices;
  // The clearance step puts every vertex but the neckline's corner and its
  // neighbour back after each round (as the skin and the rest of the
  // dress would; the neckline goes on past vertices 0 and 3), so only
  // rounding the neckline's corner can part the fold.
  int pushes = 0;
  const auto hold = [&] {
    ++pushes;
    for (int v = 0; v < m.num_vertices(); ++v)
      if (v != 1 && v != 2) m.vertices.row(v) = before.row(v);
  };
  EXPECT_EQ(untangle(m.vertices, m.faces, opening, hold), 0);
  EXPECT_EQ(self_pairs(m), 0);
  EXPECT_GT(pushes, kUntangleRounds);  // the opening had to move
  // A local repair: the corner moves by less than an edge (2.5 cm).
  EXPECT_LT((m.vertices - before).rowwise().norm().maxCoeff(), 0.025f);
}

TEST(GarmentUntangle, WhatSmoothingInsideTheOpeningsPartsKeepsTheOpenings) {
  // The same fold with nothing holding the vertices off the neckline:
  // the first rounds part it and the neckline does not move.
  geometry::TriMesh m = folded_neckline_corner();
  const std::vector<std::uint8_t> opening = {1, 1, 1, 1, 0, 0, 0, 0, 0, 0, 0, 0, 0};
  const geometry::Points before = m.vertices;
  int pushes = 0;
  EXPECT_EQ(untangle(m.vertices, m.faces, opening, [&] { ++pushes; }), 0);
  EXPECT_LE(pushes, kUntangleRounds);
  for (int v = 0; v < 4; ++v) EXPECT_EQ(m.vertices.row(v), before.row(v)) << "neckline vertex " << v;
}

TEST(GarmentUntangle, AMeshThatDoesNotCrossItselfIsLeftAsItWas) {
  geometry::TriMesh m;  // a 3 x 3 grid of 1 cm cells, slightly curved
  m.vertices.resize(16, 3);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) m.vertices.row(j * 4 + i) << 0.01f * i, 0.01f * j, 0.002f * (i - 1.5f) * (i - 1.5f);
  m.faces.resize(18, 3);
  for (int j = 0, f = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const int v = j * 4 + i;
      m.faces.row(f++) << v, v + 1, v + 5;
      m.faces.row(f++) << v, v + 5, v + 4;
    }
  const geometry::TriMesh before = m;
  int pushes = 0;
  EXPECT_EQ(untangle(m.vertices, m.faces, std::vector<std::uint8_t>(16, 0), [&] { ++pushes; }), 0);
  EXPECT_EQ(pushes, 0);
  EXPECT_EQ(m.vertices, before.vertices);
}

TEST(GarmentUntangle, CrossingsThatStayAreCountedAfterEveryRound) {
  // Two closed tetrahedra through each other about one centre (a stellated
  // octahedron, the second 1.3 times larger so that edges pierce faces),
  // with a clearance step that undoes every move: all rounds run and the
  // pairs left are returned.
  geometry::TriMesh m;
  m.vertices.resize(8, 3);
  const float c[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
  for (int v = 0; v < 4; ++v) {
    m.vertices.row(v) << 0.01f * c[v][0], 0.01f * c[v][1], 0.01f * c[v][2];
    m.vertices.row(4 + v) << -0.013f * c[v][0], -0.013f * c[v][1], -0.013f * c[v][2];
  }
  m.faces.resize(8, 3);
  m.faces << 0, 1, 2, 0, 3, 1, 0, 2, 3, 1, 3, 2, 4, 5, 6, 4, 7, 5, 4, 6, 7, 5, 7, 6;
  ASSERT_GT(self_pairs(m), 0);
  const geometry::Points before = m.vertices;
  int pushes = 0;
  const auto undo = [&] {
    ++pushes;
    m.vertices = before;
  };
  const std::int64_t left = untangle(m.vertices, m.faces, std::vector<std::uint8_t>(8, 0), undo);
  EXPECT_EQ(left, self_pairs(m));
  EXPECT_GT(left, 0);
  EXPECT_EQ(pushes, 2 * kUntangleRounds);
  EXPECT_GT(self_pairs(m), 0);
}

}  // namespace
}  // namespace layers::garment
