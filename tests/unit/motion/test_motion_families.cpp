// Parametric motion families: the replayable description, the stress
// ranges (smooth, grounded, starting at rest), hop, mirrored clips and
// clip windows.
#include <gtest/gtest.h>

#include "body_fixture.h"
#include "layers/core/error.h"
#include "layers/motion/clip_ops.h"
#include "layers/motion/procedural.h"

namespace layers::motion {
namespace {

std::vector<body::JointTransforms> track(const MotionSource& m, const body::Body& b) {
  std::vector<body::JointTransforms> t;
  for (int f = 0; f < m.num_frames(); ++f) t.push_back(body::forward_kinematics(b.skeleton, m.pose(f)));
  return t;
}

// The hardest parameters stress.yaml draws, for every kind.
ProceduralParams stress(const std::string& kind, int frames) {
  ProceduralParams p;
  p.kind = kind;
  p.frames = frames;
  p.seed = 5;
  p.speed = 1.75;
  p.amplitude = 1.5;
  p.phase = 0.37;
  p.step_length = 1.4;
  p.turn_angle = kind == "spin" ? 360.0 : kind == "turn" ? 270.0 : 0.0;
  p.direction = kind == "spin" || kind == "turn" ? -1 : 0;
  p.variant = procedural_variants(kind).empty() ? -1 : static_cast<int>(procedural_variants(kind).size()) - 1;
  p.explicit_params = true;
  return p;
}

TEST(MotionFamilies, DescriptionReplaysTheMotion) {
  const body::Body& b = body::test::body();
  for (const std::string& kind : procedural_kinds()) {
    const ProceduralParams p = stress(kind, 30);
    const std::string text = describe_procedural(p);
    ASSERT_EQ(text.rfind("procedural:" + kind + " speed=1.750 amplitude=1.500 phase=0.370", 0), 0u) << text;
    const ProceduralParams q = parse_procedural(text.substr(11), 30, 999, "motion");
    EXPECT_EQ(describe_procedural(q), text);
    const auto a = make_procedural(p, b), c = make_procedural(q, b);
    EXPECT_EQ(a->describe(), text);
    for (int f = 0; f < 30; f += 7) EXPECT_EQ((a->pose(f).root - c->pose(f).root).norm(), 0.0) << kind;
  }
  EXPECT_EQ(describe_procedural(sample_procedural("walk", 10, 3)), "procedural:walk");  // plain stays plain
  EXPECT_THROW(parse_procedural("walk pace=2", 10, 0, "motion"), InputError);
  EXPECT_THROW(parse_procedural("walk speed=fast", 10, 0, "motion"), InputError);
  EXPECT_THROW(parse_procedural("walk variant=left", 10, 0, "motion"), InputError);
  EXPECT_THROW(make_procedural(parse_procedural("walk phase=1.5", 10, 0, "motion"), b), InputError);
}

TEST(MotionFamilies, StressParametersStaySmoothGroundedAndStartAtRest) {
  const body::Body& b = body::test::body();
  for (const std::string& kind : procedural_kinds()) {
    const auto m = make_procedural(stress(kind, 75), b);
    const auto t = track(*m, b);
    double d2 = 0.0, lowest = 1.0, start = 0.0;
    for (int j = 0; j < b.skeleton.num_joints(); ++j)
      start = std::max(start, (t[1].position[j] - t[0].position[j]).norm());
    for (int f = 1; f + 1 < m->num_frames(); ++f) {
      for (int j = 0; j < b.skeleton.num_joints(); ++j)
        d2 = std::max(d2, (t[f + 1].position[j] - 2 * t[f].position[j] + t[f - 1].position[j]).norm());
      const auto soles = sole_heights(b, t[f]);
      lowest = std::min({lowest, soles[0], soles[1]});
    }
    EXPECT_LT(start, 0.003) << kind << ": moving at frame 0";
    // 225 m/s^2 (the plain motions stay under 180, test_procedural.cpp): a
    // 4.4 m/s run with 1.4x strides swings its feet that hard.
    EXPECT_LT(d2, 0.25) << kind;
    EXPECT_GT(lowest, -0.005) << kind << ": a sole below the ground";
  }
}

TEST(MotionFamilies, HopLeavesTheGroundRepeatedly) {
  const body::Body& b = body::test::body();
  const auto m = make_procedural(stress("hop", 90), b);
  const auto t = track(*m, b);
  int flights = 0;
  bool up = false;
  for (const auto& x : t) {
    const auto soles = sole_heights(b, x);
    const bool air = std::min(soles[0], soles[1]) > 0.02;
    flights += air && !up;
    up = air;
  }
  EXPECT_GE(flights, 3);  // 3 s at 1.75x: a hop every ~0.5 s (0.22 s on the ground) once started
}

TEST(MotionFamilies, MirroredPoseIsTheMirrorImage) {
  const body::Body& b = body::test::body();
  const body::Skeleton& sk = b.skeleton;
  const PoseMirror mirror(sk);
  const int lw = sk.require("LeftHand"), rw = sk.require("RightHand");
  EXPECT_EQ(mirror.partner(lw), rw);
  EXPECT_EQ(mirror.partner(0), 0);
  ProceduralParams p = stress("arm_raise", 40);
  p.variant = 1;  // front-left: only the left arm rises
  const auto m = make_procedural(p, b);
  double worst = 0.0, moved = 0.0;
  for (int f = 0; f < 40; f += 3) {
    const body::JointTransforms a = body::forward_kinematics(sk, m->pose(f));
    const body::JointTransforms c = body::forward_kinematics(sk, mirror(m->pose(f)));
    for (const auto& [x, y] : {std::pair{lw, rw}, std::pair{rw, lw}}) {
      const body::Vec3 reflected(-a.position[y].x(), a.position[y].y(), a.position[y].z());
      worst = std::max(worst, (c.position[x] - reflected).norm());
    }
    moved = std::max(moved, (a.position[lw] - c.position[lw]).norm());
  }
  EXPECT_LT(worst, 0.01);  // the rest skeleton is symmetric to within this
  EXPECT_GT(moved, 0.2);   // and the mirror is not the original
}

// Every joint of a mirrored CMU frame sits at the mirror image of its
// partner (LHipJoint and RThumb pair up too, not only Left* and Right*).
TEST(MotionFamilies, MirroredClipIsTheMirrorImage) {
  const body::Body& b = body::test::body();
  const PoseMirror mirror(b.skeleton);
  EXPECT_EQ(mirror.partner(b.skeleton.require("LHipJoint")), b.skeleton.require("RHipJoint"));
  EXPECT_EQ(mirror.partner(b.skeleton.require("RThumb")), b.skeleton.require("LThumb"));
  MotionSpec spec;
  spec.frames = 20;
  spec.motion = "cmu/131_02_start_walk_stop.bvh window=150+20 mirror=0";
  const auto plain = make_motion(spec, b);
  spec.motion = "cmu/131_02_start_walk_stop.bvh window=150+20 mirror=1";
  const auto mirrored = make_motion(spec, b);
  double worst = 0.0;
  for (int f : {0, 9, 19}) {
    const auto a = body::forward_kinematics(b.skeleton, plain->pose(f));
    const auto c = body::forward_kinematics(b.skeleton, mirrored->pose(f));
    for (int j = 0; j < b.skeleton.num_joints(); ++j) {
      const body::Vec3& p = a.position[mirror.partner(j)];
      worst = std::max(worst, (c.position[j] - body::Vec3(-p.x(), p.y(), p.z())).norm());
    }
  }
  EXPECT_LT(worst, 0.01);
}

TEST(MotionFamilies, ClipWindowStartsAtRestInsideTheClip) {
  const body::Body& b = body::test::body();
  const auto clip = make_procedural(stress("walk", 120), b);
  const std::vector<body::Pose>& poses = clip->poses();
  const std::vector<body::Pose> w = clip_window(poses, 60, 50, 15);
  ASSERT_EQ(w.size(), 50u);
  // After the 15-frame ease-in the window plays the clip from frame 60 + 10.
  const body::Vec3 offset = w[20].root - poses[75].root;
  for (int i = 15; i < 50; ++i) {
    EXPECT_LT((w[i].root - poses[60 + 10 + (i - 15)].root - offset).norm(), 1e-9) << i;
    EXPECT_LT(body::angle_of(w[i].local[3].conjugate() * poses[70 + (i - 15)].local[3]), 1e-9);
  }
  // Eased in: the first step is under a tenth of the clip's own at that frame.
  EXPECT_LT((w[1].root - w[0].root).norm(), 0.1 * (poses[61].root - poses[60].root).norm());
  EXPECT_LT(w[0].root.x() * w[0].root.x() + w[0].root.z() * w[0].root.z(), 1e-18);
  EXPECT_THROW(clip_window(poses, 80, 50), Error);
  EXPECT_THROW(clip_window(poses, -1, 10), Error);
}

TEST(MotionFamilies, ClipSpecWithWindowAndMirror) {
  const body::Body& b = body::test::body();
  MotionSpec spec;
  spec.motion = "cmu/131_01_start_walk_stop.bvh window=100+40 mirror=1";
  spec.frames = 50;
  spec.transition_frames = 10;
  const auto m = make_motion(spec, b);
  EXPECT_EQ(m->num_frames(), 50);
  EXPECT_EQ(m->describe(), "bvh:cmu/131_01_start_walk_stop.bvh window=100+40 mirror=1");
  const int n = bvh_clip_frames("cmu/131_01_start_walk_stop.bvh");
  EXPECT_GT(n, 200);
  spec.motion = "cmu/131_01_start_walk_stop.bvh window=" + std::to_string(n - 39) + "+40 mirror=0";
  EXPECT_THROW(make_motion(spec, b), InputError);  // past the clip's end
  spec.motion = "cmu/131_01_start_walk_stop.bvh window=10+30";
  EXPECT_THROW(make_motion(spec, b), InputError);  // not the motion's length
  spec.motion = "cmu/131_01_start_walk_stop.bvh mirror=2";
  EXPECT_THROW(make_motion(spec, b), InputError);
}

}  // namespace
}  // namespace layers::motion
