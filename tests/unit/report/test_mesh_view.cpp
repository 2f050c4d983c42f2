// Front views of meshes: shading by the normal's z, back-face culling,
// farthest-first order, and the frames chosen for the picture.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

#include "layers/core/error.h"
#include "layers/report/frames_picture.h"
#include "layers/report/mesh_view.h"

namespace layers::report {
namespace {

TEST(MeshView, ShadeScalesTheBaseColour) {
  EXPECT_EQ(shade(0xc86420, 1.0), 0xc86420u);
  EXPECT_EQ(shade(0xc86420, -1.0), 0xc86420u) << "both sides of a sheet face the viewer";
  EXPECT_EQ(shade(0xc86420, 0.0, 0.5), 0x643210u);
}

TEST(MeshView, CullsBackFacesAndOrdersFarthestFirst) {
  // Two triangles facing +z (counter-clockwise seen from +z) at z = 0 and
  // z = 1, and one facing -z at z = 2; a vertex with NaN makes a fourth face
  // that is skipped.
  const float p[] = {0,   0, 1, 1, 0, 1, 0, 1, 1,  // near, facing the camera
                     0,   0, 0, 1, 0, 0, 0, 1, 0,  // far, facing the camera
                     0,   0, 2, 0, 1, 2, 1, 0, 2,  // nearest, facing away
                     NAN, 0, 0};
  const std::vector<std::int32_t> faces = {0, 1, 2, 3, 4, 5, 6, 7, 8, 0, 1, 9};
  std::vector<ScreenTriangle> culled, both;
  add_mesh(culled, p, 10, faces, 0xffffff, true);
  add_mesh(both, p, 10, faces, 0xffffff, false);
  ASSERT_EQ(culled.size(), 2u);
  EXPECT_EQ(both.size(), 3u);
  const std::string data = polygon_data(culled);
  std::istringstream in(data);
  double x, y;
  unsigned rgb;
  in >> x >> y >> rgb;
  EXPECT_EQ(rgb, 0xffffffu);
  // The first polygon written is the far one (z = 0): its second vertex is (1, 0).
  in >> x >> y >> rgb;
  EXPECT_DOUBLE_EQ(x, 1.0);
  EXPECT_EQ(std::count(data.begin(), data.end(), '\n'), 8) << "3 lines and a blank line per polygon";

  // A bias larger than the 1 m gap puts the far triangle in front (written last).
  std::vector<ScreenTriangle> biased;
  add_mesh(biased, p, 10, {0, 1, 2}, 0x0000ff, true);
  add_mesh(biased, p, 10, {3, 4, 5}, 0xff0000, true, 1.5f);
  const std::string order = polygon_data(biased);
  EXPECT_LT(order.find(std::to_string(0x0000ff)), order.find(std::to_string(0xff0000)));

  std::vector<ScreenTriangle> out;
  EXPECT_THROW(add_mesh(out, p, 10, {0, 1, 10}, 0xffffff, false), Error);
  const ScreenBounds b = mesh_bounds(p, 10);
  EXPECT_EQ(b.xmin, 0.0);
  EXPECT_EQ(b.xmax, 1.0);
}

TEST(FramesPicture, FramesSpreadOverThePredictedOnes) {
  EXPECT_EQ(picture_frames(29, 4), (std::vector<std::int64_t>{2, 11, 19, 28}));
  EXPECT_EQ(picture_frames(29, 1), (std::vector<std::int64_t>{28}));
  EXPECT_EQ(picture_frames(4, 4), (std::vector<std::int64_t>{2, 3}));
  EXPECT_TRUE(picture_frames(0, 3).empty());
}

}  // namespace
}  // namespace layers::report
