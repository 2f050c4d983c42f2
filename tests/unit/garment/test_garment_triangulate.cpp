// Panel meshing: a flat outline is filled at the target edge length with
// counter-clockwise triangles that keep the outline points and edges.
#include <gtest/gtest.h>

#include <cmath>
#include <map>

#include "layers/core/error.h"
#include "layers/garment/garment_triangulate.h"

namespace layers::garment {
namespace {

// An L-shaped outline (counter-clockwise) sampled at about h.
std::vector<Vec2> l_shape(double h) {
  const std::vector<Vec2> corners = {{0, 0}, {0.5, 0}, {0.5, 0.3}, {0.2, 0.3}, {0.2, 0.6}, {0, 0.6}};
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < corners.size(); ++i) {
    const Vec2 a = corners[i], b = corners[(i + 1) % corners.size()];
    const int n = std::max(1, static_cast<int>(std::lround((b - a).norm() / h)));
    for (int k = 0; k < n; ++k) out.push_back(a + (b - a) * (static_cast<double>(k) / n));
  }
  return out;
}

double cross(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

TEST(GarmentTriangulate, FillsAnOutlineWithEvenTriangles) {
  const double h = 0.02;
  const std::vector<Vec2> outline = l_shape(h);
  const PlanarMesh m = mesh_polygon(outline, h);
  ASSERT_EQ(m.num_boundary, static_cast<int>(outline.size()));
  for (std::size_t i = 0; i < outline.size(); ++i) EXPECT_EQ(m.points[i], outline[i]);

  std::map<std::pair<int, int>, int> uses;
  double area = 0;
  int in_band = 0, edges = 0;
  for (const auto& t : m.triangles) {
    const double a = 0.5 * cross(m.points[t[1]] - m.points[t[0]], m.points[t[2]] - m.points[t[0]]);
    EXPECT_GT(a, 0.0);
    area += a;
    for (int k = 0; k < 3; ++k) {
      const int u = t[k], v = t[(k + 1) % 3];
      ++uses[{std::min(u, v), std::max(u, v)}];
      const double len = (m.points[u] - m.points[v]).norm() / h;
      in_band += len > 0.6 && len < 1.5;
      ++edges;
    }
  }
  EXPECT_NEAR(area, 0.5 * 0.3 + 0.2 * 0.3, 1e-9);
  // Every outline segment is an edge of exactly one triangle; every other edge of two.
  const int n = m.num_boundary;
  int outline_edges = 0;
  for (const auto& [e, count] : uses) {
    const bool on_outline = e.second < n && (e.second - e.first == 1 || (e.first == 0 && e.second == n - 1));
    EXPECT_EQ(count, on_outline ? 1 : 2);
    outline_edges += on_outline;
  }
  EXPECT_EQ(outline_edges, n);
  EXPECT_GT(static_cast<double>(in_band) / edges, 0.97);
  // Equilateral lattice density: about 2 / (sqrt(3) h^2) points per unit area.
  EXPECT_NEAR(m.points.size() * std::sqrt(3.0) / 2 * h * h / 0.21, 1.0, 0.15);
}

TEST(GarmentTriangulate, RejectsAClockwiseOutline) {
  std::vector<Vec2> outline = l_shape(0.05);
  std::reverse(outline.begin(), outline.end());
  EXPECT_THROW(mesh_polygon(outline, 0.05), Error);
  EXPECT_THROW(mesh_polygon({{0, 0}, {1, 0}}, 0.05), Error);
}

}  // namespace
}  // namespace layers::garment
