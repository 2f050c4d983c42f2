// Normals, areas, edges, adjacency and validation on hand-made meshes.
#include <gtest/gtest.h>

#include "grid_mesh.h"
#include "layers/core/error.h"
#include "layers/geometry/mesh.h"
#include "layers/geometry/normals.h"
#include "layers/geometry/topology.h"

namespace g = layers::geometry;

namespace {

// Unit cube [0,1]^3, 8 vertices, 12 triangles wound outwards.
g::TriMesh cube() {
  g::TriMesh m;
  m.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) m.vertices.row(i) << float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1);
  m.faces.resize(12, 3);
  m.faces << 0, 2, 1, 1, 2, 3,  // z = 0, normal -z
      4, 5, 6, 5, 7, 6,         // z = 1, normal +z
      0, 1, 4, 1, 5, 4,         // y = 0, normal -y
      2, 6, 3, 3, 6, 7,         // y = 1, normal +y
      0, 4, 2, 2, 4, 6,         // x = 0, normal -x
      1, 3, 5, 3, 7, 5;         // x = 1, normal +x
  return m;
}

// Right-angled tetrahedron at the origin, faces wound outwards.
g::TriMesh tetra() {
  g::TriMesh m;
  m.vertices.resize(4, 3);
  m.vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1;
  m.faces.resize(4, 3);
  m.faces << 0, 2, 1, 0, 1, 3, 0, 3, 2, 1, 2, 3;
  return m;
}

}  // namespace

TEST(Normals, TetraFaceNormalsAndAreas) {
  g::TriMesh t = tetra();
  g::Points fn = g::face_normals(t.vertices, t.faces);
  EXPECT_TRUE(fn.row(0).isApprox(Eigen::RowVector3f(0, 0, -1)));
  EXPECT_TRUE(fn.row(1).isApprox(Eigen::RowVector3f(0, -1, 0)));
  EXPECT_TRUE(fn.row(2).isApprox(Eigen::RowVector3f(-1, 0, 0)));
  float s = 1.0f / std::sqrt(3.0f);
  EXPECT_TRUE(fn.row(3).isApprox(Eigen::RowVector3f(s, s, s)));

  Eigen::VectorXf a = g::face_areas(t.vertices, t.faces);
  EXPECT_FLOAT_EQ(a(0), 0.5f);
  EXPECT_FLOAT_EQ(a(3), std::sqrt(3.0f) / 2.0f);
}

TEST(Normals, TetraVertexNormalsAreAreaWeighted) {
  g::TriMesh t = tetra();
  g::Points vn = g::vertex_normals(t);
  // Vertex 0 touches three faces of area 1/2 with normals -x, -y, -z.
  float s = 1.0f / std::sqrt(3.0f);
  EXPECT_TRUE(vn.row(0).isApprox(Eigen::RowVector3f(-s, -s, -s)));
  // Vertex 1: faces with normals -z, -y (area 1/2 each) and the slanted
  // face (area sqrt(3)/2, normal (1,1,1)/sqrt(3)): sum of area*normal
  // = (0,-1/2,-1/2) + (1/2,1/2,1/2) = (1/2, 0, 0).
  EXPECT_TRUE(vn.row(1).isApprox(Eigen::RowVector3f(1, 0, 0)));
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(vn.row(i).norm(), 1.0f, 1e-6f);
}

TEST(Normals, CubeVertexNormalsPointOutwards) {
  g::TriMesh c = cube();
  g::Points vn = g::vertex_normals(c);
  Eigen::RowVector3f centre(0.5f, 0.5f, 0.5f);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(vn.row(i).norm(), 1.0f, 1e-6f);
    EXPECT_GT(vn.row(i).dot(c.vertices.row(i) - centre), 0.0f) << "vertex " << i;
  }
  g::Points fn = g::face_normals(c.vertices, c.faces);
  EXPECT_TRUE(fn.row(0).isApprox(Eigen::RowVector3f(0, 0, -1)));
  EXPECT_TRUE(fn.row(11).isApprox(Eigen::RowVector3f(1, 0, 0)));
  EXPECT_NEAR(g::face_areas(c.vertices, c.faces).sum(), 6.0f, 1e-5f);
}

TEST(Normals, IsolatedAndDegenerateGiveZero) {
  g::Points v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 2, 0, 0, 5, 5, 5;  // collinear face, isolated vertex 3
  g::Faces f(1, 3);
  f << 0, 1, 2;
  EXPECT_TRUE(g::face_normals(v, f).row(0).isZero());
  EXPECT_TRUE(g::vertex_normals(v, f).isZero());
}

TEST(Topology, CubeEdgesAndAdjacency) {
  g::TriMesh c = cube();
  g::Edges e = g::unique_edges(c.faces);
  // Closed triangulated surface: E = 3F/2; Euler V - E + F = 2.
  EXPECT_EQ(e.rows(), 18);
  EXPECT_EQ(c.num_vertices() - e.rows() + c.num_faces(), 2);
  for (Eigen::Index i = 0; i < e.rows(); ++i) {
    EXPECT_LT(e(i, 0), e(i, 1));
    if (i > 0) {
      EXPECT_TRUE(e(i - 1, 0) < e(i, 0) || (e(i - 1, 0) == e(i, 0) && e(i - 1, 1) < e(i, 1)));
    }
  }
  g::Adjacency adj = g::vertex_adjacency(c.faces, c.num_vertices());
  ASSERT_EQ(adj.num_vertices(), 8);
  EXPECT_EQ(adj.neighbours.size(), 36u);
  int degree_sum = 0;
  for (int v = 0; v < 8; ++v) degree_sum += adj.degree(v);
  EXPECT_EQ(degree_sum, 36);
  // Vertex 0 is joined to 1, 2, 4 (cube edges) and to the face diagonals
  // that start there in this triangulation: none, since every diagonal
  // above runs 1-2, 1-4, 2-4, 3-6, 3-5, 5-6.
  EXPECT_EQ(std::vector<int>(adj.begin(0), adj.end(0)), (std::vector<int>{1, 2, 4}));
  EXPECT_EQ(std::vector<int>(adj.begin(1), adj.end(1)), (std::vector<int>{0, 2, 3, 4, 5}));
}

TEST(Topology, BoundaryVerticesOfAGridAndAClosedTetra) {
  const g::TriMesh grid = layers::test::unit_square_grid(4, 0.0f);
  const std::vector<char> open = g::boundary_vertices(grid.faces, 17);  // one isolated vertex
  int count = 0;
  for (int v = 0; v < 16; ++v) {
    const int i = v % 4, j = v / 4;
    EXPECT_EQ(open[v] != 0, i == 0 || i == 3 || j == 0 || j == 3) << v;
    count += open[v];
  }
  EXPECT_EQ(count, 12);
  EXPECT_EQ(open[16], 0);
  // The grid's outline: 3 edges a side, each once, sorted, i < j.
  const g::Edges outline = g::boundary_edges(grid.faces);
  ASSERT_EQ(outline.rows(), 12);
  for (Eigen::Index e = 0; e < outline.rows(); ++e) {
    EXPECT_LT(outline(e, 0), outline(e, 1));
    EXPECT_TRUE(open[outline(e, 0)] && open[outline(e, 1)]);
    if (e > 0)
      EXPECT_TRUE(std::make_pair(outline(e - 1, 0), outline(e - 1, 1)) < std::make_pair(outline(e, 0), outline(e, 1)));
  }
  g::Faces tetra(4, 3);
  tetra << 0, 2, 1, 0, 1, 3, 1, 2, 3, 0, 3, 2;
  for (char b : g::boundary_vertices(tetra, 4)) EXPECT_EQ(b, 0);
  EXPECT_EQ(g::boundary_edges(tetra).rows(), 0);
}

TEST(Topology, TetraAndIsolatedVertex) {
  g::TriMesh t = tetra();
  EXPECT_EQ(g::unique_edges(t.faces).rows(), 6);
  g::Adjacency adj = g::vertex_adjacency(t.faces, 5);
  for (int v = 0; v < 4; ++v) EXPECT_EQ(adj.degree(v), 3);
  EXPECT_EQ(adj.degree(4), 0);
}

TEST(Mesh, ValidateNamesFaceAndIndex) {
  g::TriMesh t = tetra();
  EXPECT_NO_THROW(g::validate(t, "tetra"));
  t.faces(2, 1) = 7;
  try {
    g::validate(t, "shard-00000.h5:/seq/a/garments/0");
    FAIL() << "no error";
  } catch (const layers::InputError& e) {
    EXPECT_STREQ(e.what(), "shard-00000.h5:/seq/a/garments/0: faces[2][1]: expected a vertex index in [0, 4), got 7");
  }
  t.faces(2, 1) = 0;
  EXPECT_THROW(g::validate(t, "x"), layers::InputError);
}

TEST(Mesh, ConcatenateOffsetsIndices) {
  g::TriMesh joined = g::concatenate({tetra(), cube()});
  EXPECT_EQ(joined.num_vertices(), 12);
  EXPECT_EQ(joined.num_faces(), 16);
  EXPECT_EQ(joined.faces.row(4), Eigen::RowVector3i(4, 6, 5));
  EXPECT_TRUE(joined.vertices.row(11).isApprox(Eigen::RowVector3f(1, 1, 1)));
  EXPECT_NO_THROW(g::validate(joined, "joined"));
}
