// Where a refused scene broke (libs/generate/src/refused_where.h): the
// crossing places of a hand-made frame -- a body plate, a garment pushed
// through it and a second garment through the first -- grouped by the
// nearest joint, and nothing for garments clear of everything.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "refused_where.h"

namespace layers::generate {
namespace {

// A square of two triangles at height y, x and z in [x0, x0 + size].
void square(std::vector<float>& points, std::vector<std::int32_t>& faces, float x0, float y, float size) {
  const auto base = static_cast<std::int32_t>(points.size() / 3);
  for (const auto& [x, z] :
       std::vector<std::pair<float, float>>{{x0, 0}, {x0 + size, 0}, {x0 + size, size}, {x0, size}})
    points.insert(points.end(), {x, y, z});
  faces.insert(faces.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

// A vertical square (x fixed) crossing the horizontal plane y = 0 at z in
// [0.2, 0.4], y in [-0.1, 0.1].
void wall(std::vector<float>& points, std::vector<std::int32_t>& faces, float x) {
  const auto base = static_cast<std::int32_t>(points.size() / 3);
  points.insert(points.end(), {x, -0.1f, 0.2f, x, 0.1f, 0.2f, x, 0.1f, 0.4f, x, -0.1f, 0.4f});
  faces.insert(faces.end(), {base, base + 1, base + 2, base, base + 2, base + 3});
}

data::SequenceData frame_with(bool through_body) {
  data::SequenceData seq;
  seq.id = "seq-000000";
  seq.n_frames = 1;
  square(seq.body.positions, seq.body.faces, 0, 0, 1);  // the body: a 1 m plate at y = 0
  seq.body.joint_names = {"LeftHand", "RightHand"};
  seq.body.joint_parents = {-1, 0};
  seq.body.skin_index.assign(4 * 4, 0);  // four vertices, all on the first joint
  seq.body.skin_weight.assign(4 * 4, 0.25f);
  // Joint world transforms [R | p], row-major 3x4: identity at x = 0.2 and x = 0.8.
  for (const float x : {0.2f, 0.8f})
    seq.body.joints.insert(seq.body.joints.end(), {1, 0, 0, x, 0, 1, 0, 0.3f, 0, 0, 1, 0.3f});
  data::GarmentData dress, jacket;
  dress.name = "dress";
  jacket.name = "jacket";
  jacket.layer = 1;
  if (through_body) {
    wall(dress.rest, dress.faces, 0.15f);  // through the plate, near LeftHand
  } else {
    square(dress.rest, dress.faces, 0.1f, 0.05f, 0.3f);  // over it, clear
  }
  dress.positions = dress.rest;
  // The jacket: a horizontal square above the plate, through the dress's wall when it stands.
  square(jacket.rest, jacket.faces, 0.05f, 0.05f, 0.5f);
  jacket.positions = jacket.rest;
  seq.garments = {dress, jacket};
  seq.wind.strength = {0};
  seq.wind.rotation = {1, 0, 0, 0};
  return seq;
}

TEST(RefusedWhere, CrossingsAreNamedByGarmentAndNearestJoint) {
  const std::vector<std::string> lines = crossing_places(frame_with(true), 0, 0.018, 3);
  ASSERT_EQ(lines.size(), 3u);  // dress through the body, dress through jacket, jacket through dress
  EXPECT_EQ(lines[0].rfind("dress through the body: 2 faces, near LeftHand 2 at (0.150, ", 0), 0u) << lines[0];
  EXPECT_EQ(lines[1].rfind("dress through jacket: ", 0), 0u) << lines[1];
  EXPECT_EQ(lines[2].rfind("jacket through dress: ", 0), 0u) << lines[2];
  EXPECT_NE(lines[2].find("near LeftHand"), std::string::npos) << lines[2];
}

TEST(RefusedWhere, GarmentsClearOfEverythingHaveNoPlace) {
  EXPECT_TRUE(crossing_places(frame_with(false), 0, 0.018, 3).empty());
  // A frame that is not stored: nothing, no crash.
  EXPECT_TRUE(crossing_places(frame_with(true), 5, 0.018, 3).empty());
}

}  // namespace
}  // namespace layers::generate
