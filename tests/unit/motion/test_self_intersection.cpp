// Body self-intersection: clean rest poses, detection of an arm pushed into
// the torso, repair by abduction, and the frame policies.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "body_fixture.h"
#include "layers/body/pose_body.h"
#include "layers/body/self_intersection.h"
#include "layers/core/error.h"
#include "layers/motion/body_sequence.h"
#include "layers/motion/procedural.h"

namespace layers::motion {
namespace {

using body::test::shape;

// The rest pose with the left upper arm turned `angle` rad toward the body
// (about the forward axis).
body::Pose arm_in(const body::Body& b, double angle) {
  body::Pose p = body::rest_pose(b.skeleton);
  p.local[b.skeleton.require("LeftArm")] = body::rot_z(-angle);
  return p;
}

// The rest pose with both legs turned `angle` rad toward each other (about
// the forward axis).
body::Pose legs_in(const body::Body& b, double angle) {
  body::Pose p = body::rest_pose(b.skeleton);
  p.local[b.skeleton.require("LeftUpLeg")] = body::rot_z(-angle);
  p.local[b.skeleton.require("RightUpLeg")] = body::rot_z(angle);
  return p;
}

TEST(SelfIntersection, RestPosesAreClean) {
  for (const body::ShapeParams& s :
       {shape(0.5, 0.5, 0.5, 0.5), shape(0, 0, 0, 0), shape(1, 1, 1, 1), shape(0, 1, 1, 0.5)}) {
    const body::Body& b = body::test::body(s);
    const body::SelfIntersection si(b);
    const body::FrameIntersection r = si.check(b.rest.vertices);
    EXPECT_LT(r.depth, si.options().tolerance) << s.gender << " " << s.muscle << " " << s.weight;
  }
}

TEST(SelfIntersection, PartsCoverTheBody) {
  const body::Body& b = body::test::body();
  const body::SelfIntersection si(b);
  std::array<int, body::kNumBodyParts + 1> count{};
  for (int p : si.part()) ++count[p + 1];
  for (int p = 1; p <= body::kNumBodyParts; ++p)
    EXPECT_GT(count[p], 1000) << body::body_part_name(static_cast<body::BodyPart>(p - 1));
  EXPECT_LT(count[0], b.num_vertices() / 5);  // blend zones stay small
}

TEST(SelfIntersection, DetectsAnArmInTheTorso) {
  const body::Body& b = body::test::body();
  const body::SelfIntersection si(b);
  const body::FrameIntersection r = si.check(body::pose_body(b, arm_in(b, 0.9)).vertices);
  EXPECT_GT(r.depth, 0.01);
  EXPECT_GT(r.limb_depth[0], 0.01);  // left arm
  EXPECT_LT(r.limb_depth[1], 1e-9);  // right arm untouched
  EXPECT_GT(r.vertices, 10);
}

TEST(SelfIntersection, ExactCrossingsSeeWhatTheNearestVertexTestMisses) {
  const body::Body& b = body::test::body();
  // The left arm down and swung across the back: its hand sits inside the
  // lower back, deeper than the nearest-vertex test's reach.
  body::Pose p = body::rest_pose(b.skeleton);
  p.local[b.skeleton.require("LeftArm")] = body::rot_x(0.6) * body::rot_z(-1.2);
  const geometry::Points posed = body::pose_body(b, p).vertices;
  const body::SelfIntersection exact(b);
  const body::FrameIntersection r = exact.check(posed);
  EXPECT_FALSE(r.offends());  // the depth verdict is blind here
  EXPECT_GT(r.limb_crossings[0], 20);
  EXPECT_EQ(r.limb_crossings[1], 0);
  EXPECT_TRUE(r.needs_repair());
  body::IntersectionOptions o;
  o.exact = false;
  EXPECT_EQ(body::SelfIntersection(b, o).check(posed).crossings, 0);
  // Rest poses have no crossings between regions.
  EXPECT_EQ(exact.check(b.rest.vertices).crossings, 0);
}

TEST(SelfIntersection, SequencesResolveSmallIntersections) {
  const body::Body& b = body::test::body();
  // 40 frames: the left arm sinks into the torso (a little) and back.
  std::vector<body::Pose> poses;
  for (int f = 0; f < 40; ++f) poses.push_back(arm_in(b, 0.95 * std::sin(M_PI * f / 39.0)));
  const PoseTrack motion(poses, "test:arm");
  const BodySequence seq = generate_body_sequence(b, motion);
  EXPECT_GT(seq.intersection.intersecting, 0);
  EXPECT_EQ(seq.intersection.remaining, 0);
  EXPECT_EQ(seq.num_frames, 40);
  EXPECT_LE(seq.intersection.worst_after, 0.004);
  EXPECT_GT(seq.intersection.crossing_before, 0);
  EXPECT_EQ(seq.intersection.crossing_after, 0);
  EXPECT_EQ(seq.intersection.crossing_limbs, 2);  // the arms
  // Every written frame is clean.
  const body::SelfIntersection si(b);
  for (int f = 0; f < seq.num_frames; ++f) {
    const body::FrameIntersection r = si.check(frame_vertices(seq, f));
    EXPECT_LE(r.depth, 0.004) << "frame " << f;
    EXPECT_EQ(r.limb_crossings[0], 0) << "frame " << f;  // the arm's exact crossings cleared too
  }
}

TEST(SelfIntersection, ArmGapIsTheRoomUnderTheArm) {
  const body::Body& b = body::test::body();
  const body::SelfIntersection si(b);
  // Arms out in the T-pose: nothing of them near the torso.
  const body::FrameIntersection t = si.check(body::pose_body(b, b.t_pose).vertices);
  EXPECT_TRUE(std::isinf(t.arm_gap[0]));
  EXPECT_TRUE(std::isinf(t.arm_gap[1]));
  // The left arm turned toward the body: its gap shrinks step by step to
  // contact; the right arm's stays as it was.
  const double right = si.check(body::pose_body(b, arm_in(b, 0.0)).vertices).arm_gap[1];
  double last = std::numeric_limits<double>::infinity();
  for (double angle : {0.5, 0.6, 0.7}) {
    const body::FrameIntersection r = si.check(body::pose_body(b, arm_in(b, angle)).vertices);
    EXPECT_LT(r.arm_gap[0], last) << angle;
    EXPECT_GE(r.arm_gap[0], 0.0);
    EXPECT_EQ(r.arm_gap[1], right);
    last = r.arm_gap[0];
  }
  EXPECT_LT(last, 0.01);
}

// The left arm turned in until it is within `room` of the torso but not
// inside it (the angle, 0.01 rad steps). Its faces already cross the
// torso's at the shoulder's blend zone.
double arm_near(const body::Body& b, const body::SelfIntersection& si, double room) {
  for (double angle = 0.4; angle < 1.0; angle += 0.01) {
    const body::FrameIntersection r = si.check(body::pose_body(b, arm_in(b, angle)).vertices);
    if (r.arm_gap[0] < room && r.depth == 0.0) return angle;
  }
  return -1.0;
}

TEST(SelfIntersection, GapAsksForRoomWhereTheDepthAllowsContact) {
  const body::Body& b = body::test::body();
  const body::SelfIntersection depth_only(b);
  body::IntersectionOptions o;
  o.gap = 0.004;
  const body::SelfIntersection gapped(b, o);
  const double angle = arm_near(b, depth_only, 0.003);
  ASSERT_GT(angle, 0.0);
  const geometry::Points posed = body::pose_body(b, arm_in(b, angle)).vertices;
  const body::FrameIntersection plain = depth_only.check(posed);
  EXPECT_FALSE(plain.offends());
  const body::FrameIntersection r = gapped.check(posed);
  EXPECT_TRUE(r.offends());
  EXPECT_GE(r.limb_shortfall[0], 0.004 - plain.arm_gap[0] - 1e-9);  // at least what the arm's gap lacks
  EXPECT_LT(r.limb_shortfall[1], 0.0);                              // the right arm has its room
  EXPECT_EQ(r.depth, 0.0);
  // The rest pose keeps the room everywhere it is asked.
  EXPECT_FALSE(gapped.check(b.rest.vertices).offends());
}

TEST(SelfIntersection, SequencesKeepTheGapAndSayHowMuchTheyTurned) {
  const body::Body& b = body::test::body();
  const double angle = arm_near(b, body::SelfIntersection(b), 0.002);
  ASSERT_GT(angle, 0.0);
  // 40 frames: the left arm comes within 2 mm of the torso and goes back.
  std::vector<body::Pose> poses;
  for (int f = 0; f < 40; ++f) poses.push_back(arm_in(b, angle * std::sin(M_PI * f / 39.0)));
  const PoseTrack motion(poses, "test:near");
  SequenceOptions o;
  o.on_intersection = "keep";
  o.intersection.exact = false;  // the shoulder's crossings would steer the repair too
  const BodySequence plain = generate_body_sequence(b, motion, o);
  EXPECT_EQ(plain.intersection.intersecting, 0);
  EXPECT_EQ(plain.intersection.corrected, 0);
  EXPECT_EQ(plain.intersection.max_turn, 0.0);
  o.intersection.gap = 0.004;
  const BodySequence seq = generate_body_sequence(b, motion, o);
  EXPECT_GT(seq.intersection.intersecting, 0);
  EXPECT_EQ(seq.intersection.remaining, 0);
  EXPECT_GE(seq.intersection.corrected, seq.intersection.intersecting);  // the spread turns neighbours too
  EXPECT_LT(seq.intersection.corrected, 40);
  EXPECT_GT(seq.intersection.max_turn, 0.0);
  EXPECT_LE(seq.intersection.max_turn, o.max_arm_correction + 1e-9);
  EXPECT_GT(seq.intersection.max_shift, 0.002);  // the hand moves more than the gap lacked
  const body::SelfIntersection si(b, o.intersection);
  for (int f = 0; f < seq.num_frames; ++f) EXPECT_FALSE(si.check(frame_vertices(seq, f)).offends()) << "frame " << f;
}

// 60 frames: the rest pose, with `pose(s)` in frames 20-40 (s rising from
// 0 to 1 at frame 30 and back), made without and with the room `ask` sets
// (every frame kept).
struct RoomPair {
  BodySequence plain, roomy;
  RoomPair(const body::Body& b, const std::function<body::Pose(double)>& pose,
           const std::function<void(SequenceOptions&)>& ask) {
    std::vector<body::Pose> poses;
    for (int f = 0; f < 60; ++f) poses.push_back(pose(f < 20 || f > 40 ? 0.0 : std::sin(M_PI * (f - 20) / 20.0)));
    const PoseTrack motion(poses, "test:room");
    SequenceOptions o;
    o.on_intersection = "keep";
    plain = generate_body_sequence(b, motion, o);
    ask(o);
    roomy = generate_body_sequence(b, motion, o);
  }
  // Some frames turned, not all of those that move (40), by no more than `limit`.
  static void expect_some_turned(const RoomReport& room, double limit) {
    EXPECT_GT(room.frames, 0);
    EXPECT_LT(room.frames, 40);
    EXPECT_GT(room.turn, 0.0);
    EXPECT_LE(room.turn, limit + 1e-9);
  }
  // Frames of `roomy` that are those of `plain`.
  int unchanged() const {
    int n = 0;
    for (int f = 0; f < plain.num_frames; ++f)
      n += frame_vertices(roomy, f).isApprox(frame_vertices(plain, f), 0.0) ? 1 : 0;
    return n;
  }
};

TEST(SelfIntersection, ArmRoomTurnsOnlyTheFramesThatNeedIt) {
  const body::Body& b = body::test::body();
  const body::SelfIntersection si(b);
  // The left arm comes down near the side (2.5 cm from it at the lowest,
  // no intersection) and goes back out; the right arm stays where it is.
  // 4 cm of room asked for.
  const double room = 0.04;
  const RoomPair r(
      b, [&](double s) { return arm_in(b, 0.6 * s); }, [&](SequenceOptions& o) { o.arm_room = room; });
  EXPECT_EQ(r.plain.intersection.arm_room.frames, 0);
  ASSERT_EQ(r.roomy.num_frames, 60);
  RoomPair::expect_some_turned(r.roomy.intersection.arm_room, SequenceOptions{}.max_arm_room_turn);
  for (int f = 0; f < 60; ++f) {
    // Every frame has the room asked for (the turns stay under the limit here).
    EXPECT_GE(si.check(frame_vertices(r.roomy, f)).arm_gap[0], room - 1e-6) << "frame " << f;
  }
  EXPECT_GE(r.unchanged(), 10);  // frames far from the side are left as they were
}

// 40 frames: the left arm at `side` (arm_in) in frames 0-19, then swung
// far forward and in, 2.3 cm from the torso, where abduction about the
// chest's forward axis brings it closer (1.6 cm at 0.3 rad). Made without
// and with `room` of arm room (no repair, every frame kept); gap(s, f) is
// the left arm's gap in frame f of s.
struct ArmRoomPair {
  const body::Body& b = body::test::body();
  const body::SelfIntersection si{b};
  BodySequence plain, roomy;
  ArmRoomPair(double side, double room) {
    body::Pose swung = body::rest_pose(b.skeleton);
    swung.local[b.skeleton.require("LeftArm")] = body::rot_x(-1.2) * body::rot_z(-1.1);
    std::vector<body::Pose> poses;
    for (int f = 0; f < 40; ++f) poses.push_back(f < 20 ? arm_in(b, side) : swung);
    const PoseTrack motion(poses, "test:arm room, swung forward");
    SequenceOptions o;
    o.on_intersection = "keep";
    o.resolve = false;
    plain = generate_body_sequence(b, motion, o);
    o.arm_room = room;
    roomy = generate_body_sequence(b, motion, o);
  }
  double gap(const BodySequence& s, int f) const {
    return si.check(frame_vertices(s, f), {false, false, false, false}).arm_gap[0];
  }
};

TEST(SelfIntersection, ArmRoomNeverTakesAnArmCloserToTheTorso) {
  // Frames 0-19: near the side, where abduction opens the room; frames
  // 20-39 need it too, but abduction would take the arm closer.
  const double room = 0.04;
  ArmRoomPair r(0.6, room);
  ASSERT_EQ(r.roomy.num_frames, 40);
  ASSERT_LT(r.gap(r.plain, 30), 0.03);
  ASSERT_GT(r.gap(r.plain, 30), 0.015);
  for (int f = 0; f < 40; ++f) EXPECT_GE(r.gap(r.roomy, f), std::min(r.gap(r.plain, f), room) - 0.003) << "frame " << f;
  EXPECT_GE(r.gap(r.roomy, 5), room - 1e-6);  // where abduction helps, it is used
  EXPECT_GT(r.roomy.intersection.arm_room.frames, 0);
}

TEST(SelfIntersection, ArmRoomSpreadSparesFramesThatHaveTheRoom) {
  // Frames 0-19 need a turn for 2 cm of room; frames 20-39 have it but
  // abduction would take it away. The spread of frame 19's turn must stop
  // short of them.
  const double room = 0.02;
  ArmRoomPair r(0.8, room);
  ASSERT_EQ(r.roomy.num_frames, 40);
  ASSERT_LT(r.gap(r.plain, 5), room);   // the first frames need room ...
  ASSERT_GE(r.gap(r.plain, 25), room);  // ... the last have it
  EXPECT_GT(r.roomy.intersection.arm_room.frames, 0);
  for (int f = 0; f < 40; ++f) EXPECT_GE(r.gap(r.roomy, f), std::min(r.gap(r.plain, f), room) - 0.003) << "frame " << f;
}

TEST(SelfIntersection, ThighGapIsTheRoomBetweenTheLegs) {
  const body::Body& b = body::test::body();
  const body::SelfIntersection si(b);
  // The rest pose's legs stand apart: nothing of one near the other.
  EXPECT_TRUE(std::isinf(si.check(body::pose_body(b, legs_in(b, 0.0)).vertices).thigh_gap));
  // The legs turned toward each other: the gap shrinks step by step to
  // contact (5 cm, 3.7, 2.0, 0.4 on this body).
  double last = std::numeric_limits<double>::infinity();
  for (double angle : {0.15, 0.17, 0.18, 0.19}) {
    const body::FrameIntersection r = si.check(body::pose_body(b, legs_in(b, angle)).vertices);
    EXPECT_LT(r.thigh_gap, last) << angle;
    EXPECT_GE(r.thigh_gap, 0.0);
    EXPECT_LT(r.depth, si.options().tolerance) << angle;  // close, not inside
    last = r.thigh_gap;
  }
  EXPECT_LT(last, 0.006);
  // The arms' gaps do not see the legs (the left arm near the side, so
  // that its gap is measured).
  const auto pose = [&](double legs) {
    body::Pose p = legs_in(b, legs);
    p.local[b.skeleton.require("LeftArm")] = arm_in(b, 0.6).local[b.skeleton.require("LeftArm")];
    return si.check(body::pose_body(b, p).vertices);
  };
  const body::FrameIntersection apart = pose(0.0), close = pose(0.19);
  ASSERT_TRUE(std::isfinite(apart.arm_gap[0]));
  EXPECT_EQ(apart.arm_gap, close.arm_gap);
  EXPECT_LT(close.thigh_gap, apart.thigh_gap);
}

TEST(SelfIntersection, ThighRoomTurnsOnlyTheFramesThatNeedIt) {
  const body::Body& b = body::test::body();
  const body::SelfIntersection si(b);
  // The legs come together (1.2 cm apart at the closest, no intersection)
  // and go back; 3 cm of room asked for.
  const double room = 0.03;
  const RoomPair r(
      b, [&](double s) { return legs_in(b, 0.185 * s); }, [&](SequenceOptions& o) { o.thigh_room = room; });
  const auto gap = [&](const BodySequence& q, int f) {
    return si.check(frame_vertices(q, f), {false, false, false, false}).thigh_gap;
  };
  EXPECT_EQ(r.plain.intersection.thigh_room.frames, 0);
  ASSERT_LT(gap(r.plain, 30), 0.015);
  ASSERT_GE(gap(r.plain, 0), room);
  ASSERT_EQ(r.roomy.num_frames, 60);
  RoomPair::expect_some_turned(r.roomy.intersection.thigh_room, SequenceOptions{}.max_thigh_room_turn);
  EXPECT_EQ(r.roomy.intersection.arm_room.frames, 0);  // the arms are not asked for room
  // Every frame has the room asked for (the turns stay under the limit here).
  for (int f = 0; f < 60; ++f) EXPECT_GE(gap(r.roomy, f), room - 1e-6) << "frame " << f;
  EXPECT_GE(r.unchanged(), 10);  // frames far from the other leg are left as they were
}

TEST(SelfIntersection, PoliciesForFramesThatStayIntersecting) {
  const body::Body& b = body::test::body();
  // Frames 10..14 push the arm deep into the torso (beyond any repair).
  std::vector<body::Pose> poses;
  for (int f = 0; f < 30; ++f) poses.push_back(f >= 10 && f < 15 ? arm_in(b, 2.0) : body::rest_pose(b.skeleton));
  const PoseTrack motion(poses, "test:deep");
  SequenceOptions o;
  o.resolve = false;
  o.on_intersection = "longest_run";
  BodySequence seq = generate_body_sequence(b, motion, o);
  EXPECT_EQ(seq.num_frames, 15);
  EXPECT_EQ(seq.source_frame.front(), 15);
  EXPECT_EQ(seq.intersection.dropped, 15);
  o.on_intersection = "first_run";  // the frames before the first bad one
  seq = generate_body_sequence(b, motion, o);
  EXPECT_EQ(seq.num_frames, 10);
  EXPECT_EQ(seq.source_frame.front(), 0);
  EXPECT_EQ(seq.source_frame.back(), 9);
  o.on_intersection = "drop";
  seq = generate_body_sequence(b, motion, o);
  EXPECT_EQ(seq.num_frames, 25);
  EXPECT_EQ(seq.source_frame[10], 15);
  o.on_intersection = "keep";
  seq = generate_body_sequence(b, motion, o);
  EXPECT_EQ(seq.num_frames, 30);
  EXPECT_EQ(seq.intersection.remaining, 5);
  EXPECT_NEAR(seq.intersection.share_intersecting(), 5.0 / 30.0, 1e-12);
  o.on_intersection = "sometimes";
  EXPECT_THROW(generate_body_sequence(b, motion, o), InputError);
}

TEST(SelfIntersection, SequenceArraysHaveTheH5Shapes) {
  const body::Body& b = body::test::body();
  const auto m = make_procedural(sample_procedural("wave", 20, 1), b);
  const BodySequence seq = generate_body_sequence(b, *m);
  ASSERT_EQ(seq.num_frames, 20);
  EXPECT_EQ(seq.positions.size(), 20u * b.num_vertices() * 3);
  EXPECT_EQ(seq.root.size(), 20u * 3);
  EXPECT_EQ(seq.root_rot.size(), 20u * 4);
  EXPECT_EQ(seq.joints.size(), 20u * 31 * 12);
  // root_rot is a unit quaternion; joints[.., 0, :, 3] is the root position.
  for (int f = 0; f < 20; ++f) {
    double n = 0.0;
    for (int k = 0; k < 4; ++k) n += seq.root_rot[4 * f + k] * seq.root_rot[4 * f + k];
    EXPECT_NEAR(n, 1.0, 1e-5);
    for (int k = 0; k < 3; ++k) EXPECT_FLOAT_EQ(seq.joints[f * 31 * 12 + 4 * k + 3], seq.root[3 * f + k]);
  }
}

}  // namespace
}  // namespace layers::motion
