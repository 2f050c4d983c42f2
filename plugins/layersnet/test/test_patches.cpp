// LayersNet patches from UV charts on hand-made grids: which faces form a
// patch, which vertices belong to it, which patches E^M joins.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "grid.h"
#include "layers/core/error.h"
#include "patches.h"

namespace ln = layers::layersnet;

namespace {

using Members = std::vector<std::int64_t>;
using Edge = std::pair<std::int64_t, std::int64_t>;

// A grid of cols x rows unit cells (vertex (i,j) = j*(cols+1)+i), two
// triangles per cell (grid.h), UVs = vertex coordinates, one panel.
ln::PatchInput grid(int cols, int rows) {
  ln::PatchInput in;
  const int n = cols + 1;
  in.n_vertices = static_cast<std::int64_t>(n) * (rows + 1);
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= cols; ++i) in.uv.insert(in.uv.end(), {static_cast<float>(i), static_cast<float>(j)});
  in.faces = layers::test::grid_faces(rows + 1, n);
  in.uv_faces = in.faces;
  in.panel.assign(in.faces.size() / 3, 0);
  return in;
}

Members members(const ln::GarmentPatches& p, std::int64_t k) {
  return Members(p.members.begin() + p.offsets[k], p.members.begin() + p.offsets[k + 1]);
}

// Vertices (i, j) of a grid with `cols` cells per row, i in [i0,i1], j in [j0,j1].
Members block(int cols, int i0, int i1, int j0, int j1) {
  Members m;
  for (int j = j0; j <= j1; ++j)
    for (int i = i0; i <= i1; ++i) m.push_back(static_cast<std::int64_t>(j) * (cols + 1) + i);
  std::sort(m.begin(), m.end());
  return m;
}

}  // namespace

TEST(Patches, StripWithTwoPanelsInSeparateCharts) {
  // 6 x 2 cells; cells with x >= 4 form panel 1, whose chart lies 10 UV
  // units to the right (its own UV vertices), sewn to panel 0 in 3D.
  ln::PatchInput in = grid(6, 2);
  const std::int64_t n_uv = static_cast<std::int64_t>(in.uv.size() / 2);
  for (std::size_t f = 0; f < in.panel.size(); ++f) {
    const std::int64_t cell_x = (in.faces[3 * f] % 7 + in.faces[3 * f + 1] % 7 + in.faces[3 * f + 2] % 7) / 3;
    if (cell_x < 4) continue;
    in.panel[f] = 1;
    for (int k = 0; k < 3; ++k) in.uv_faces[3 * f + k] += n_uv;  // the shifted copy below
  }
  const std::vector<float> shifted = [&] {
    std::vector<float> s = in.uv;
    for (std::size_t i = 0; i < s.size(); i += 2) s[i] += 10.0f;
    return s;
  }();
  in.uv.insert(in.uv.end(), shifted.begin(), shifted.end());

  const ln::GarmentPatches p = ln::build_patches(in, 2.0, "strip");
  ASSERT_EQ(p.size(), 3);
  EXPECT_EQ(p.cell[0], (std::array<std::int64_t, 3>{0, 0, 0}));
  EXPECT_EQ(p.cell[1], (std::array<std::int64_t, 3>{0, 1, 0}));
  EXPECT_EQ(p.cell[2], (std::array<std::int64_t, 3>{1, 7, 0}));  // u in [14, 16)
  EXPECT_EQ(members(p, 0), block(6, 0, 2, 0, 2));
  EXPECT_EQ(members(p, 1), block(6, 2, 4, 0, 2));
  EXPECT_EQ(members(p, 2), block(6, 4, 6, 0, 2));
  // Neighbours along the strip (also across the seam); the ends never touch.
  EXPECT_EQ(p.mesh_edges, (std::vector<Edge>{{0, 1}, {1, 2}}));
}

TEST(Patches, CornerVertexJoinsFourPatches) {
  // 4 x 3 cells at patch size 2: cells (u,v) = (0|1, 0|1); the top row of
  // patches is one cell high. Vertex (2,2) is in all four patches.
  const ln::GarmentPatches p = ln::build_patches(grid(4, 3), 2.0, "grid");
  ASSERT_EQ(p.size(), 4);
  EXPECT_EQ(p.cell[1], (std::array<std::int64_t, 3>{0, 0, 1}));
  EXPECT_EQ(members(p, 0), block(4, 0, 2, 0, 2));
  EXPECT_EQ(members(p, 1), block(4, 0, 2, 2, 3));
  EXPECT_EQ(members(p, 2), block(4, 2, 4, 0, 2));
  EXPECT_EQ(members(p, 3), block(4, 2, 4, 2, 3));
  EXPECT_EQ(p.mesh_edges, (std::vector<Edge>{{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}}));
}

TEST(Patches, FacesJoinByCentroid) {
  // 3 x 1 cells at patch size 1.5: triangle (a,b,d) of cell i has its
  // centroid at u = i + 2/3, (a,d,c) at u = i + 1/3, so the middle cell
  // splits: (1,2,6) joins cell 1, (1,6,5) cell 0.
  const ln::GarmentPatches p = ln::build_patches(grid(3, 1), 1.5, "thin");
  ASSERT_EQ(p.size(), 2);
  EXPECT_EQ(members(p, 0), (Members{0, 1, 4, 5, 6}));
  EXPECT_EQ(members(p, 1), (Members{1, 2, 3, 6, 7}));
  EXPECT_EQ(p.mesh_edges, (std::vector<Edge>{{0, 1}}));
}

TEST(Patches, CellsWithoutFacesMakeNoPatch) {
  // An L: 4 x 4 cells without the top-right 2 x 2 block, at patch size 2.
  ln::PatchInput in = grid(4, 4);
  ln::PatchInput l = in;
  l.faces.clear();
  l.panel.clear();
  for (std::size_t f = 0; f < in.faces.size() / 3; ++f) {
    const std::int64_t a = in.faces[3 * f];  // the cell's lower-left vertex
    if (a % 5 >= 2 && a / 5 >= 2) continue;
    l.faces.insert(l.faces.end(), in.faces.begin() + 3 * f, in.faces.begin() + 3 * f + 3);
    l.panel.push_back(0);
  }
  l.uv_faces = l.faces;
  const ln::GarmentPatches p = ln::build_patches(l, 2.0, "L");
  ASSERT_EQ(p.size(), 3);
  EXPECT_EQ(p.cell[2], (std::array<std::int64_t, 3>{0, 1, 0}));
  EXPECT_EQ(members(p, 1), block(4, 0, 2, 2, 4));
  // Patches 1 and 2 share only vertex (2,2).
  EXPECT_EQ(p.mesh_edges, (std::vector<Edge>{{0, 1}, {0, 2}, {1, 2}}));
}

TEST(Patches, RejectsBadInput) {
  EXPECT_THROW(ln::build_patches(grid(2, 2), 0.0, "g"), layers::InputError);
  ln::PatchInput bad = grid(2, 2);
  bad.uv_faces[4] = 1000;
  try {
    ln::build_patches(bad, 1.0, "garments[0] (shirt)");
    FAIL() << "no error";
  } catch (const layers::InputError& e) {
    EXPECT_EQ(e.file(), "garments[0] (shirt)");
    EXPECT_EQ(e.field(), "uv_faces");
  }
  ln::PatchInput short_panel = grid(2, 2);
  short_panel.panel.pop_back();
  EXPECT_THROW(ln::build_patches(short_panel, 1.0, "g"), layers::InputError);
  ln::PatchInput nan_uv = grid(2, 2);
  nan_uv.uv[3] = std::numeric_limits<float>::quiet_NaN();
  EXPECT_THROW(ln::build_patches(nan_uv, 1.0, "g"), layers::InputError);
}
