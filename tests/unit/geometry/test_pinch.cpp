// Pinch zones of a body (pinch.h): none on a flat sheet (coarse or fine),
// the faces of two plates closer than the pinch distance, and the ring
// around the body's own crossings.
#include <gtest/gtest.h>

#include <algorithm>

#include "grid_mesh.h"
#include "layers/geometry/pinch.h"

namespace g = layers::geometry;

namespace {

// The unit-square grid with n x n vertices scaled to `size` metres, at height z.
g::TriMesh plate(int n, float size, float z, float dx = 0) {
  g::TriMesh m = layers::test::unit_square_grid(n, z);
  for (int i = 0; i < m.num_vertices(); ++i) {
    m.vertices(i, 0) = m.vertices(i, 0) * size + dx;
    m.vertices(i, 1) *= size;
  }
  return m;
}

long count(const std::vector<char>& flags) { return static_cast<long>(std::count(flags.begin(), flags.end(), 1)); }

}  // namespace

TEST(Pinch, AFlatSheetHasNone) {
  const g::TriMesh sheet = plate(11, 0.1f, 0);  // 1 cm edges
  EXPECT_EQ(count(g::pinch_faces(sheet, {}, 0.018)), 0);
  // Nor one whose edges are much shorter than the distance.
  const g::TriMesh fine = plate(41, 0.1f, 0);  // 2.5 mm edges
  EXPECT_EQ(count(g::pinch_faces(fine, {}, 0.018)), 0);
}

TEST(Pinch, TwoPartsCloserThanTheDistancePinchWhereTheyFaceEachOther) {
  // A 10 cm plate with a 4 cm plate 12 mm over its first 4 cm: two parts
  // of one body (separate pieces: no path along the mesh joins them).
  const g::TriMesh low = plate(11, 0.1f, 0), high = plate(5, 0.04f, 0.012f);
  const g::TriMesh body = g::concatenate({low, high});
  const std::vector<char> pinch = g::pinch_faces(body, {}, 0.018);
  // Every face of the upper plate; of the lower one those under it (and
  // one column of faces beyond its edge), none farther.
  for (int f = low.num_faces(); f < body.num_faces(); ++f) EXPECT_TRUE(pinch[f]) << f;
  for (int f = 0; f < low.num_faces(); ++f) {
    float x = 1, y = 1;
    for (int k = 0; k < 3; ++k) {
      x = std::min(x, body.vertices(body.faces(f, k), 0));
      y = std::min(y, body.vertices(body.faces(f, k), 1));
    }
    if (x < 0.035f && y < 0.035f) {
      EXPECT_TRUE(pinch[f]) << f;
    }
    if (x > 0.055f || y > 0.055f) {
      EXPECT_FALSE(pinch[f]) << f;
    }
  }
  // Farther apart than the distance: no pinch.
  EXPECT_EQ(count(g::pinch_faces(body, {}, 0.010)), 0);
}

TEST(Pinch, TheBodysOwnCrossingsAndTheirRingArePinched) {
  const g::TriMesh sheet = plate(11, 0.1f, 0);
  std::vector<char> crossing(static_cast<std::size_t>(sheet.num_faces()), 0);
  crossing[100] = 1;  // an interior face
  const std::vector<char> pinch = g::pinch_faces(sheet, crossing, 0);
  EXPECT_EQ(pinch, g::grow_faces(sheet, crossing, 1));
  EXPECT_GT(count(pinch), 1);  // the face and its neighbours
}

TEST(Pinch, ZonesUnderClothExamineOnlyTheBodyTheClothCovers) {
  // The two plates of the test above, and cloth (a few points) over the
  // corner where they face each other: the zones there are found, those
  // of the same body far from any cloth are not looked for.
  const g::TriMesh low = plate(11, 0.1f, 0), high = plate(5, 0.04f, 0.012f);
  const g::TriMesh body = g::concatenate({low, high});
  g::Points cloth(2, 3);
  cloth << 0.005f, 0.005f, 0.006f, 0.01f, 0.005f, 0.006f;
  const g::PinchZones zones = g::pinch_zones_under(body, {}, 0.018, cloth, 0.004);
  // Covered: the body vertices within 2 x 18 mm + 2 mm of a cloth point.
  for (int v = 0; v < body.num_vertices(); ++v) {
    double nearest = 1e9;
    for (int c = 0; c < cloth.rows(); ++c)
      nearest = std::min(nearest, static_cast<double>((body.vertices.row(v) - cloth.row(c)).norm()));
    EXPECT_EQ(zones.covered[v] != 0, nearest <= 0.038) << v;
  }
  EXPECT_EQ(zones.faces, g::pinch_faces(body, {}, 0.018, &zones.covered));
  EXPECT_GT(count(zones.faces), 0);
  EXPECT_LT(count(zones.faces), count(g::pinch_faces(body, {}, 0.018)));  // the far corner of the upper plate
  // No cloth: nothing covered, no zone.
  EXPECT_EQ(count(g::pinch_zones_under(body, {}, 0.018, g::Points(0, 3), 0).faces), 0);
}
