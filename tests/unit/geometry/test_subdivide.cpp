// Midpoint subdivision: counts, shared edges split once, attributes follow.
#include <gtest/gtest.h>

#include "layers/core/error.h"
#include "layers/geometry/subdivide.h"

namespace layers::geometry {
namespace {

TEST(Subdivide, TwoTrianglesSharingAnEdge) {
  // Unit square split along its diagonal 0-2.
  const std::vector<std::int32_t> faces = {0, 1, 2, 0, 2, 3};
  const Subdivision s = subdivide(faces, 4);
  EXPECT_EQ(s.faces.size(), 24u);
  EXPECT_EQ(s.midpoints.size(), 5u);  // 5 edges, the diagonal split once
  EXPECT_EQ(s.vertices(), 9);
  const std::vector<float> xy = {0, 0, 1, 0, 1, 1, 0, 1};
  // Two "frames": the second one shifted by 10 in x.
  std::vector<float> frames = xy;
  for (std::size_t i = 0; i < xy.size(); i += 2) frames.insert(frames.end(), {xy[i] + 10, xy[i + 1]});
  const std::vector<float> out = s.apply(frames, 2);
  ASSERT_EQ(out.size(), 2u * 9u * 2u);
  // The midpoint of the diagonal is the square's centre in both frames.
  for (std::size_t m = 0; m < s.midpoints.size(); ++m) {
    if (s.midpoints[m] != std::make_pair(0, 2)) continue;
    EXPECT_FLOAT_EQ(out[(4 + m) * 2], 0.5f);
    EXPECT_FLOAT_EQ(out[(4 + m) * 2 + 1], 0.5f);
    EXPECT_FLOAT_EQ(out[18 + (4 + m) * 2], 10.5f);
  }
  // Every face index is in range; twice subdivided gives 16x the faces.
  const Subdivision t = subdivide(s.faces, s.vertices());
  EXPECT_EQ(t.faces.size(), 16u * faces.size());
  for (std::int32_t v : t.faces) EXPECT_LT(v, t.vertices());
}

TEST(Subdivide, BadInputIsAnError) {
  EXPECT_THROW(subdivide({0, 1, 5}, 3), InputError);
  const Subdivision s = subdivide({0, 1, 2}, 3);
  EXPECT_THROW(s.apply({1, 2, 3}, 2), Error);
}

}  // namespace
}  // namespace layers::geometry
