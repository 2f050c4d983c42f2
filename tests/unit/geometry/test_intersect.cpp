// Exact triangle crossings: hand-made pairs that cross and that only touch,
// planted crossings between two grids, and the face tree against brute force.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "grid_mesh.h"
#include "layers/geometry/intersect.h"

namespace g = layers::geometry;
using V = g::Vec3d;

namespace {

// The unit-square grid moved by (dx, dy, 0) and scaled by s in x and y.
g::TriMesh moved_grid(int n, float z, float dx, float dy, float s) {
  g::TriMesh m = layers::test::unit_square_grid(n, z);
  for (int i = 0; i < m.num_vertices(); ++i) {
    m.vertices(i, 0) = m.vertices(i, 0) * s + dx;
    m.vertices(i, 1) = m.vertices(i, 1) * s + dy;
  }
  return m;
}

// Faces of `mesh` that use any of `vertices`.
std::set<int> faces_around(const g::TriMesh& mesh, const std::set<int>& vertices) {
  std::set<int> out;
  for (int f = 0; f < mesh.num_faces(); ++f)
    for (int k = 0; k < 3; ++k)
      if (vertices.count(mesh.faces(f, k))) out.insert(f);
  return out;
}

}  // namespace

TEST(TrianglesCross, TransversalPairCrossesBothWays) {
  const V a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  const V b0(0.2, 0.2, -0.5), b1(0.3, 0.25, 0.5), b2(0.9, 0.9, 0.4);
  EXPECT_TRUE(g::triangles_cross(a0, a1, a2, b0, b1, b2));
  EXPECT_TRUE(g::triangles_cross(b0, b1, b2, a0, a1, a2));
  EXPECT_TRUE(g::segment_crosses_triangle(b0, b1, a0, a1, a2));
}

TEST(TrianglesCross, TouchingIsNotCrossing) {
  const V a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  // A vertex resting on the face, the rest above it.
  EXPECT_FALSE(g::triangles_cross(a0, a1, a2, V(0.2, 0.2, 0), V(0.5, 0.2, 0.3), V(0.2, 0.5, 0.3)));
  // An edge lying in the face, the third vertex above.
  EXPECT_FALSE(g::triangles_cross(a0, a1, a2, V(0.1, 0.1, 0), V(0.4, 0.2, 0), V(0.2, 0.3, 0.5)));
  // Coplanar overlap.
  EXPECT_FALSE(g::triangles_cross(a0, a1, a2, V(0.1, 0.1, 0), V(0.8, 0.1, 0), V(0.1, 0.8, 0)));
  // Parallel and apart, and a segment ending on the face.
  EXPECT_FALSE(g::triangles_cross(a0, a1, a2, V(0, 0, 0.1), V(1, 0, 0.1), V(0, 1, 0.1)));
  EXPECT_FALSE(g::segment_crosses_triangle(V(0.2, 0.2, 0), V(0.2, 0.2, 1), a0, a1, a2));
}

TEST(TrianglesCross, PassingBesideTheTriangleIsNotCrossing) {
  const V a0(0, 0, 0), a1(1, 0, 0), a2(0, 1, 0);
  // Straddles the plane, but meets it outside the triangle.
  EXPECT_FALSE(g::triangles_cross(a0, a1, a2, V(0.8, 0.8, -0.5), V(0.9, 0.8, 0.5), V(0.9, 0.9, 0.5)));
  EXPECT_FALSE(g::segment_crosses_triangle(V(0.8, 0.8, -1), V(0.8, 0.8, 1), a0, a1, a2));
}

TEST(MeshCrossings, FindsEveryPlantedCrossingAndNothingElse) {
  // A cloth 1 cm over a plane (offset in x and y so that no edges line up);
  // some of its vertices are pushed 1 cm through the plane.
  const g::TriMesh plane = moved_grid(12, 0.0f, 0.0f, 0.0f, 1.0f);
  g::TriMesh cloth = moved_grid(9, 0.01f, 0.0731f, 0.0577f, 0.83f);
  const std::set<int> planted = {10, 22, 40, 41, 58, 70};
  for (int v : planted) cloth.vertices(v, 2) = -0.01f;

  const g::MeshCrossings c = g::crossings(cloth, plane);
  const std::set<int> expected = faces_around(cloth, planted);
  std::set<int> found;
  for (int f = 0; f < cloth.num_faces(); ++f)
    if (c.a_faces[f]) found.insert(f);
  EXPECT_EQ(found, expected);
  EXPECT_EQ(c.a_faces_crossing(), static_cast<std::int64_t>(expected.size()));
  EXPECT_GE(c.pairs, c.a_faces_crossing());
  std::set<int> on;
  for (int f : expected)
    for (int k = 0; k < 3; ++k) on.insert(cloth.faces(f, k));
  EXPECT_EQ(c.a_vertices_on_crossings(), static_cast<std::int64_t>(on.size()));
  EXPECT_DOUBLE_EQ(c.a_vertex_share(), static_cast<double>(on.size()) / cloth.num_vertices());

  // The other way round, the plane's faces that the cloth passes through.
  const g::MeshCrossings back = g::crossings(plane, cloth);
  EXPECT_EQ(back.pairs, c.pairs);
  EXPECT_GT(back.a_faces_crossing(), 0);
}

TEST(MeshCrossings, ContactWithoutCrossingCountsNothing) {
  const g::TriMesh plane = moved_grid(12, 0.0f, 0.0f, 0.0f, 1.0f);
  // Some vertices rest exactly on the plane.
  g::TriMesh resting = moved_grid(9, 0.01f, 0.0731f, 0.0577f, 0.83f);
  for (int v : {10, 22, 40, 41}) resting.vertices(v, 2) = 0.0f;
  EXPECT_EQ(g::crossings(resting, plane).pairs, 0);
  // A whole cloth lying in the plane (coplanar overlap everywhere).
  const g::TriMesh lying = moved_grid(9, 0.0f, 0.0731f, 0.0577f, 0.83f);
  const g::MeshCrossings c = g::crossings(lying, plane);
  EXPECT_EQ(c.pairs, 0);
  EXPECT_EQ(c.a_vertex_share(), 0.0);
  // A cloth 1 mm over the plane.
  EXPECT_EQ(g::crossings(moved_grid(9, 0.001f, 0.0731f, 0.0577f, 0.83f), plane).pairs, 0);
}

TEST(MeshCrossings, ClothThroughAClosedBox) {
  g::TriMesh cube;
  cube.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) cube.vertices.row(i) << float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1);
  cube.faces.resize(12, 3);
  cube.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7,
      5;
  // A sheet at mid height, larger than the box: it crosses the four sides;
  // a sheet wholly inside crosses nothing (it is inside, not crossing).
  EXPECT_GT(g::crossings(moved_grid(7, 0.5f, -0.31f, -0.27f, 1.6f), cube).pairs, 0);
  EXPECT_EQ(g::crossings(moved_grid(7, 0.5f, 0.21f, 0.23f, 0.5f), cube).pairs, 0);
}

// body_crossings: the garments as one mesh in order, against a body mesh
// or a body tree built once (the evaluation's prediction and ground truth).
TEST(MeshCrossings, BodyCrossingsAgainstAMeshOrAPrebuiltTree) {
  g::TriMesh cube;
  cube.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) cube.vertices.row(i) << float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1);
  cube.faces.resize(12, 3);
  cube.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7,
      5;
  const std::vector<g::TriMesh> garments = {moved_grid(7, 0.5f, 0.21f, 0.23f, 0.5f),
                                            moved_grid(7, 0.5f, -0.31f, -0.27f, 1.6f)};
  const g::MeshCrossings by_mesh = g::body_crossings(garments, cube);
  const g::FaceTree tree(cube);
  const g::MeshCrossings by_tree = g::body_crossings(garments, tree);
  EXPECT_GT(by_mesh.pairs, 0);
  EXPECT_EQ(by_tree.pairs, by_mesh.pairs);
  EXPECT_EQ(by_tree.a_vertices, by_mesh.a_vertices);
  ASSERT_EQ(by_mesh.a_vertices.size(), 98u);
  // The first garment lies inside the box: none of its vertices count.
  EXPECT_EQ(std::count(by_mesh.a_vertices.begin(), by_mesh.a_vertices.begin() + 49, 1), 0);
  EXPECT_EQ(g::crossings(garments[1], tree).a_vertices_on_crossings(), by_mesh.a_vertices_on_crossings());
}

// A "body" made of a floor (z = 0) and a wall (x = 0.52) sunk through it as
// one mesh: the faces along their seam cross each other, nothing else
// does. A garment patch through the floor beside the seam counts as an
// H-crossing only until the seam's faces (and one ring around them) are
// left out; a patch through the floor away from the seam always counts.
TEST(SelfCrossings, FindTheSeamOfTwoSunkPartsAndLeaveItOut) {
  const g::TriMesh floor = moved_grid(8, 0.0f, 0.0f, 0.0f, 1.0f);
  g::TriMesh wall = layers::test::unit_square_grid(8, 0.0f);
  for (int i = 0; i < wall.num_vertices(); ++i) {
    const float u = wall.vertices(i, 0);
    wall.vertices.row(i) << 0.52f, wall.vertices(i, 1), -0.23f + 0.5f * u;
  }
  const g::TriMesh body = g::concatenate({floor, wall});
  const g::FaceTree tree(body);
  const g::MeshCrossings self = g::self_crossings(tree);
  EXPECT_GT(self.pairs, 0);
  for (int f = 0; f < body.num_faces(); ++f) {
    float lo = 1e9f, hi = -1e9f;  // the face's extent across the seam
    const int axis = f < floor.num_faces() ? 0 : 2;
    const float seam = f < floor.num_faces() ? 0.52f : 0.0f;
    for (int k = 0; k < 3; ++k) {
      lo = std::min(lo, body.vertices(body.faces(f, k), axis));
      hi = std::max(hi, body.vertices(body.faces(f, k), axis));
    }
    EXPECT_EQ(self.a_faces[f] == 1, lo < seam && seam < hi) << "face " << f;
  }
  // Neighbours that share an edge or a corner never count.
  EXPECT_EQ(g::self_crossings(g::FaceTree(floor)).pairs, 0);

  const auto patch = [](float x, float y) {
    g::TriMesh m;
    m.vertices.resize(4, 3);
    m.vertices << x, y, -0.1f, x, y + 0.08f, -0.1f, x, y + 0.08f, 0.1f, x, y, 0.1f;
    m.faces.resize(2, 3);
    m.faces << 0, 1, 2, 0, 2, 3;
    return m;
  };
  const std::vector<g::TriMesh> beside = {patch(0.55f, 0.31f)}, away = {patch(0.2f, 0.31f)};
  const std::vector<char> seam = g::grow_faces(body, self.a_faces, 1);
  EXPECT_GT(std::count(seam.begin(), seam.end(), 1), std::count(self.a_faces.begin(), self.a_faces.end(), 1));
  EXPECT_EQ(g::body_crossings(beside, tree).a_vertices_on_crossings(), 4);
  EXPECT_EQ(g::body_crossings(beside, tree, seam).pairs, 0);
  EXPECT_EQ(g::body_crossings(away, tree).a_vertices_on_crossings(), 4);
  EXPECT_EQ(g::body_crossings(away, tree, seam).a_vertices_on_crossings(), 4);
}

TEST(MeshCrossings, NonFiniteFacesCrossNothing) {
  const g::TriMesh plane = moved_grid(6, 0.0f, 0.0f, 0.0f, 1.0f);
  g::TriMesh cloth = moved_grid(5, 0.01f, 0.0731f, 0.0577f, 0.83f);
  cloth.vertices(12, 2) = std::numeric_limits<float>::quiet_NaN();
  EXPECT_EQ(g::crossings(cloth, plane).pairs, 0);
  EXPECT_EQ(g::crossings(plane, cloth).pairs, 0);
}

TEST(FaceTree, AgreesWithBruteForceOnATriangleSoup) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(0.0f, 1.0f), d(-0.08f, 0.08f);
  const auto soup = [&](int n) {
    g::TriMesh m;
    m.vertices.resize(3 * n, 3);
    m.faces.resize(n, 3);
    for (int f = 0; f < n; ++f) {
      const Eigen::RowVector3f c(u(rng), u(rng), u(rng));
      for (int k = 0; k < 3; ++k) m.vertices.row(3 * f + k) = c + Eigen::RowVector3f(d(rng), d(rng), d(rng));
      m.faces.row(f) << 3 * f, 3 * f + 1, 3 * f + 2;
    }
    return m;
  };
  const g::TriMesh a = soup(300), b = soup(400);
  std::int64_t brute = 0;
  const auto corner = [](const g::TriMesh& m, int f, int k) {
    return m.vertices.row(m.faces(f, k)).cast<double>().transpose().eval();
  };
  for (int f = 0; f < a.num_faces(); ++f)
    for (int h = 0; h < b.num_faces(); ++h)
      brute += g::triangles_cross(corner(a, f, 0), corner(a, f, 1), corner(a, f, 2), corner(b, h, 0), corner(b, h, 1),
                                  corner(b, h, 2));
  EXPECT_GT(brute, 10);
  EXPECT_EQ(g::crossings(a, b).pairs, brute);
}
