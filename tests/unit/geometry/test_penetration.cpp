// The nearest-vertex penetration test against a plane and a cube.
#include <gtest/gtest.h>

#include "grid_mesh.h"
#include "layers/core/error.h"
#include "layers/geometry/penetration.h"

namespace g = layers::geometry;

TEST(Surface, PlaneAboveAndBelow) {
  g::Surface s = g::Surface::from_mesh(layers::test::unit_square_grid(5, 0.0f));
  EXPECT_EQ(s.size(), 25);
  EXPECT_TRUE(s.normals().row(12).isApprox(Eigen::RowVector3f(0, 0, 1)));
  EXPECT_FLOAT_EQ(s.offset(Eigen::RowVector3f(0.3f, 0.6f, 0.25f)), 0.25f);
  EXPECT_FLOAT_EQ(s.offset(Eigen::RowVector3f(0.3f, 0.6f, -0.1f)), -0.1f);

  g::Points x(4, 3);
  x << 0.1f, 0.1f, 0.01f, 0.5f, 0.5f, -0.01f, 0.9f, 0.2f, -0.3f, 0.5f, 0.5f, 0.0f;
  auto behind = s.behind(x);
  EXPECT_FALSE(behind(0));
  EXPECT_TRUE(behind(1));
  EXPECT_TRUE(behind(2));
  EXPECT_FALSE(behind(3));  // on the surface is not behind
  EXPECT_EQ(s.count_behind(x), 2);
}

TEST(Surface, InsideCubeIsBehind) {
  g::TriMesh c;
  c.vertices.resize(8, 3);
  for (int i = 0; i < 8; ++i) c.vertices.row(i) << float(i & 1), float((i >> 1) & 1), float((i >> 2) & 1);
  c.faces.resize(12, 3);
  c.faces << 0, 2, 1, 1, 2, 3, 4, 5, 6, 5, 7, 6, 0, 1, 4, 1, 5, 4, 2, 6, 3, 3, 6, 7, 0, 4, 2, 2, 4, 6, 1, 3, 5, 3, 7, 5;
  g::Surface s = g::Surface::from_mesh(c, "cube");
  EXPECT_TRUE(s.behind(Eigen::RowVector3f(0.5f, 0.5f, 0.5f)));
  EXPECT_TRUE(s.behind(Eigen::RowVector3f(0.9f, 0.9f, 0.8f)));
  EXPECT_FALSE(s.behind(Eigen::RowVector3f(1.2f, 1.1f, 1.3f)));
  EXPECT_FALSE(s.behind(Eigen::RowVector3f(-0.2f, -0.1f, -0.15f)));
  // The test is only as good as the mesh is fine: a point 0.2 outside the
  // middle of a face, as far from the face as from its corners, reads as
  // behind, since the corner normals lean away from it. Body and garment
  // meshes have edges far shorter than such distances.
  EXPECT_TRUE(s.behind(Eigen::RowVector3f(-0.2f, 0.5f, 0.5f)));
}

TEST(Surface, EmptyAndMismatched) {
  g::Surface empty;
  EXPECT_FALSE(empty.behind(Eigen::RowVector3f(0, 0, 0)));
  EXPECT_TRUE(std::isnan(empty.offset(Eigen::RowVector3f(0, 0, 0))));
  EXPECT_THROW(g::Surface(g::Points::Zero(3, 3), g::Points::Zero(2, 3)), layers::Error);
  g::TriMesh bad = layers::test::unit_square_grid(2, 0.0f);
  bad.faces(0, 0) = 9;
  EXPECT_THROW(g::Surface::from_mesh(bad, "body"), layers::InputError);
}
