// SkinUntangler: a deep hip and knee flexion folds the skin into itself
// (linear blend skinning); pushing the crossing sheets apart removes every
// crossing off the hands and feet, moves only vertices near the folds, by
// at most a few centimetres, and never a hand or a foot.
#include <gtest/gtest.h>

#include "body_fixture.h"
#include "layers/body/pose_body.h"
#include "layers/body/rotation.h"
#include "layers/body/skin_untangle.h"
#include "layers/core/error.h"
#include "layers/geometry/intersect.h"

namespace layers::body {
namespace {

// Both hips flexed and both knees bent by `angle` rad (a deep squat's legs).
geometry::Points folded(const Body& b, double angle) {
  Pose p = rest_pose(b.skeleton);
  for (const char* hip : {"LeftUpLeg", "RightUpLeg"}) p.local[b.skeleton.require(hip)] = rot_x(-angle);
  for (const char* knee : {"LeftLeg", "RightLeg"}) p.local[b.skeleton.require(knee)] = rot_x(angle);
  return pose_body(b, p).vertices;
}

TEST(SkinUntangle, PushesTheFoldsOfADeepFlexionApart) {
  const Body& b = test::body();
  const geometry::Points before = folded(b, 1.5);
  const SkinUntangler untangler(b);
  const int crossing = untangler.crossing_faces(before);
  ASSERT_GT(crossing, 50);  // the fixture must fold the skin
  // The count leaves out hands, feet and head, whose fingers and toes touch
  // at rest.
  ASSERT_EQ(untangler.crossing_faces(b.rest.vertices), 0);
  ASSERT_GT(
      geometry::self_crossings(geometry::FaceTree(geometry::TriMesh{b.rest.vertices, b.rest.faces})).a_faces_crossing(),
      0);

  SkinUntangleOptions options;
  options.passes = 20;
  geometry::Points after = before;
  const SkinUntangleResult r = untangler.apply(after, options);
  EXPECT_EQ(r.crossing_before, crossing);
  EXPECT_EQ(r.crossing_after, untangler.crossing_faces(after));
  EXPECT_EQ(r.crossing_after, 0) << r.crossing_before << " -> " << r.crossing_after;
  EXPECT_GT(r.moved, 0);
  EXPECT_LT(r.moved, b.num_vertices() / 10);  // the folds, not the whole skin

  int changed = 0;
  for (Eigen::Index v = 0; v < before.rows(); ++v) {
    const double d = (after.row(v) - before.row(v)).norm();
    if (d == 0) continue;
    ++changed;
    EXPECT_TRUE(untangler.movable(static_cast<int>(v))) << "vertex " << v << " on a hand or a foot moved";
    EXPECT_LT(d, 0.03) << "vertex " << v;
  }
  EXPECT_EQ(changed, r.moved);

  // Fewer rounds leave more of the folds.
  options.passes = 1;
  geometry::Points once = before;
  EXPECT_GT(untangler.apply(once, options).crossing_after, r.crossing_after);
}

TEST(SkinUntangle, OffOrCleanLeavesTheSkinAsItIs) {
  const Body& b = test::body();
  const SkinUntangler untangler(b);
  geometry::Points v = folded(b, 1.5);
  const geometry::Points copy = v;
  const SkinUntangleResult off = untangler.apply(v, SkinUntangleOptions{});
  EXPECT_EQ(off.moved, 0);
  EXPECT_TRUE(v == copy);

  // The rest pose crosses itself only where fingers and toes touch: nothing
  // may move.
  geometry::Points rest = b.rest.vertices;
  SkinUntangleOptions on;
  on.passes = 3;
  const SkinUntangleResult clean = untangler.apply(rest, on);
  EXPECT_EQ(clean.crossing_before, 0);
  EXPECT_EQ(clean.crossing_after, 0);
  EXPECT_EQ(clean.moved, 0);
  EXPECT_TRUE(rest == b.rest.vertices);
}

TEST(SkinUntangle, RejectsAWrongVertexCountAndNegativeSettings) {
  const Body& b = test::body();
  const SkinUntangler untangler(b);
  geometry::Points wrong(10, 3);
  wrong.setZero();
  SkinUntangleOptions on;
  on.passes = 1;
  EXPECT_THROW(untangler.apply(wrong, on), InputError);
  geometry::Points v = b.rest.vertices;
  on.margin = -1;
  EXPECT_THROW(untangler.apply(v, on), InputError);
}

}  // namespace
}  // namespace layers::body
