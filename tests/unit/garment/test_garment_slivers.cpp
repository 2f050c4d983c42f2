// Sliver repair after lifting panels to 3D: a face flattened in 3D but
// healthy in UV gets its longest edge flipped, or (two corners lifted onto
// one point) its inner corner relaxed; healthy meshes are left alone.
#include <gtest/gtest.h>

#include <cmath>

#include "layers/garment/garment_pattern.h"

namespace layers::garment {
namespace {

double area3(const GarmentMesh& m, int f) {
  const body::Vec3 a = m.vertices.row(m.faces(f, 0)).cast<double>().transpose();
  const body::Vec3 b = m.vertices.row(m.faces(f, 1)).cast<double>().transpose();
  const body::Vec3 c = m.vertices.row(m.faces(f, 2)).cast<double>().transpose();
  return 0.5 * (b - a).cross(c - a).norm();
}

// A flat n x n grid in one panel, UV = (x, y), 3D = (x, y, 0), 1 cm cells.
GarmentMesh grid(int n) {
  GarmentMesh m;
  const int side = n + 1;
  m.vertices.resize(side * side, 3);
  m.uv.resize(side * side, 2);
  for (int j = 0; j < side; ++j)
    for (int i = 0; i < side; ++i) {
      m.vertices.row(j * side + i) << 0.01f * i, 0.01f * j, 0.0f;
      m.uv.row(j * side + i) << 0.01f * i, 0.01f * j;
    }
  m.faces.resize(2 * n * n, 3);
  for (int j = 0, f = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v = j * side + i;
      m.faces.row(f++) << v, v + 1, v + side + 1;
      m.faces.row(f++) << v, v + side + 1, v + side;
    }
  m.uv_faces = m.faces;
  m.panel = Eigen::VectorXi::Zero(m.num_faces());
  return m;
}

double min_area(const GarmentMesh& m) {
  double out = 1e9;
  for (int f = 0; f < m.num_faces(); ++f) out = std::min(out, area3(m, f));
  return out;
}

TEST(GarmentSlivers, HealthyMeshIsUntouched) {
  GarmentMesh m = grid(4);
  const GarmentMesh before = m;
  EXPECT_EQ(repair_slivers(m), 0);
  EXPECT_EQ(m.faces, before.faces);
  EXPECT_EQ(m.vertices, before.vertices);
}

TEST(GarmentSlivers, FlipsAFaceFlattenedAlongAStraightOutline) {
  // Two faces: (a, b, c) with b lifted onto the line a-c (a sliver in 3D,
  // a proper triangle in UV) and (a, c, d).
  GarmentMesh m;
  m.vertices.resize(4, 3);
  m.vertices << 0, 0, 0, 0.01f, 0.00002f, 0, 0.02f, 0, 0, 0.01f, -0.01f, 0;
  m.uv.resize(4, 2);
  m.uv << 0, 0, 0.01f, 0.01f, 0.02f, 0, 0.01f, -0.01f;
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 0, 2, 3;
  m.uv_faces = m.faces;
  m.panel = Eigen::VectorXi::Zero(2);
  ASSERT_LT(min_area(m), 1e-6);
  EXPECT_EQ(repair_slivers(m), 1);
  EXPECT_GT(min_area(m), 2e-5);
  EXPECT_EQ(m.vertices(1, 1), 0.00002f);  // nothing moved
  // Still one panel's consistently wound pair over the same four corners.
  for (int f = 0; f < 2; ++f) EXPECT_NE(m.faces(f, 0) + m.faces(f, 1) + m.faces(f, 2), 0 + 1 + 2);
}

TEST(GarmentSlivers, RelaxesACornerLiftedOntoItsNeighbour) {
  GarmentMesh m = grid(4);
  m.vertices.row(12) = m.vertices.row(13);  // inner vertex on top of its right neighbour
  ASSERT_LT(min_area(m), 1e-9);
  EXPECT_GT(repair_slivers(m), 0);
  for (int f = 0; f < m.num_faces(); ++f) EXPECT_GT(area3(m, f), 0.1 * 0.5e-4) << f;
}

}  // namespace
}  // namespace layers::garment
