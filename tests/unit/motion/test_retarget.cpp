// Retargeting the shipped CMU clips onto the rig: every rig joint mapped,
// limb directions follow the BVH, bone lengths constant, feet on the
// ground in stance.
#include <gtest/gtest.h>

#include <set>

#include "body_fixture.h"
#include "layers/core/error.h"
#include "layers/motion/bvh.h"
#include "layers/motion/motion.h"
#include "layers/motion/retarget.h"

namespace layers::motion {
namespace {

const char* kClips[] = {"cmu/131_01_start_walk_stop.bvh", "cmu/131_02_start_walk_stop.bvh"};

struct Retargeted {
  BvhClip clip;
  std::unique_ptr<PoseTrack> motion;
};

Retargeted load(const std::string& name, const body::Body& body) {
  Retargeted r;
  r.clip = resample(read_bvh(body::test::clip_path(name)), kFramesPerSecond);
  r.motion = retarget(r.clip, body);
  return r;
}

TEST(Retarget, NameMapCoversTheRig) {
  const body::Body& b = body::test::body();
  std::set<std::string> mapped;
  for (const auto& [bvh, rig] : cmu_3dsmax_names()) mapped.insert(rig);
  for (const std::string& name : b.skeleton.names) EXPECT_TRUE(mapped.count(name)) << name;
  const BvhClip clip = read_bvh(body::test::clip_path(kClips[0]));
  for (const auto& [bvh, rig] : cmu_3dsmax_names()) EXPECT_GE(clip.index(bvh), 0) << bvh;
}

TEST(Retarget, LimbDirectionsFollowTheClip) {
  const body::Body& b = body::test::body();
  const Retargeted r = load(kClips[0], b);
  ASSERT_EQ(r.motion->num_frames(), r.clip.num_frames());
  // Rig bone (head joint, tail joint) and the BVH joints at the same places;
  // leg directions may differ by the few degrees of the foot-contact IK.
  const std::pair<std::array<const char*, 2>, std::array<const char*, 2>> bones[] = {
      {{"LeftArm", "LeftForeArm"}, {"LeftShoulder", "LeftElbow"}},
      {{"RightForeArm", "RightHand"}, {"RightElbow", "RightWrist"}},
      {{"LeftUpLeg", "LeftLeg"}, {"LeftHip", "LeftKnee"}},
      {{"RightLeg", "RightFoot"}, {"RightKnee", "RightAnkle"}},
      {{"Spine", "Spine1"}, {"Chest", "Chest2"}},
      {{"LeftFoot", "LeftToeBase"}, {"LeftAnkle", "LeftToe"}},
  };
  for (int f = 0; f < r.clip.num_frames(); f += 7) {
    const body::JointTransforms t = body::forward_kinematics(b.skeleton, r.motion->pose(f));
    const BvhWorld w = bvh_world(r.clip, f);
    for (const auto& [rig, bvh] : bones) {
      const body::Vec3 a = t.position[b.skeleton.require(rig[1])] - t.position[b.skeleton.require(rig[0])];
      const body::Vec3 c = w.position[r.clip.index(bvh[1])] - w.position[r.clip.index(bvh[0])];
      const bool leg = std::string(rig[0]).find("Leg") != std::string::npos;
      EXPECT_GT(a.normalized().dot(c.normalized()), std::cos(leg ? 0.3 : 0.01)) << rig[0] << " frame " << f;
    }
  }
}

TEST(Retarget, BoneLengthsAreConstantInEveryFrame) {
  const body::Body& b = body::test::body();
  const body::Skeleton& sk = b.skeleton;
  for (const char* name : kClips) {
    const Retargeted r = load(name, b);
    double worst = 0.0;
    for (int f = 0; f < r.motion->num_frames(); ++f) {
      const body::JointTransforms t = body::forward_kinematics(sk, r.motion->pose(f));
      for (int j = 1; j < sk.num_joints(); ++j) {
        const int p = sk.parents[j];
        const double rest = (sk.rest_head[j] - sk.rest_head[p]).norm();
        worst = std::max(worst, std::abs((t.position[j] - t.position[p]).norm() - rest));
      }
    }
    EXPECT_LT(worst, 1e-9) << name;
  }
}

TEST(Retarget, FeetStayOnTheGroundInStance) {
  const body::Body& b = body::test::body();
  const body::Skeleton& sk = b.skeleton;
  const int ball[2] = {sk.require("LeftToeBase"), sk.require("RightToeBase")};
  const int ankle[2] = {sk.require("LeftFoot"), sk.require("RightFoot")};
  for (const char* name : kClips) {
    const Retargeted r = load(name, b);
    const int n = r.motion->num_frames();
    std::vector<body::JointTransforms> t;
    for (int f = 0; f < n; ++f) t.push_back(body::forward_kinematics(sk, r.motion->pose(f)));
    int stance = 0;
    double worst = 0.0;
    for (int f = 1; f + 1 < n; ++f) {
      const auto soles = sole_heights(b, t[f]);
      for (int s = 0; s < 2; ++s) {
        // Stance: the ball of the foot nearly still and the ankle low.
        body::Vec3 v = (t[f + 1].position[ball[s]] - t[f - 1].position[ball[s]]) * (kFramesPerSecond / 2);
        v.y() = 0.0;
        if (v.norm() > 0.15 || t[f].position[ankle[s]].y() > 0.14) continue;
        ++stance;
        worst = std::max(worst, std::abs(soles[s]));
      }
    }
    EXPECT_GT(stance, n / 2) << name;
    EXPECT_LT(worst, 0.03) << name;
  }
}

TEST(Retarget, MotionSpecsFindTheShippedClips) {
  const body::Body& b = body::test::body();
  MotionSpec spec;
  spec.motion = "cmu/131_02_start_walk_stop.bvh";
  spec.frames = 60;
  spec.transition_frames = 10;
  const auto m = make_motion(spec, b);
  EXPECT_EQ(m->num_frames(), 60);
  EXPECT_EQ(m->describe(), "bvh:cmu/131_02_start_walk_stop.bvh");  // relative to the asset root
  // Frame 0 is the T-pose where the clip starts; the clip's first pose follows.
  const body::JointTransforms t0 = body::forward_kinematics(b.skeleton, m->pose(0));
  const auto soles = sole_heights(b, t0);
  EXPECT_LT(std::abs(std::min(soles[0], soles[1])), 0.02);
  spec.frames = 100000;
  EXPECT_THROW(make_motion(spec, b), InputError);
  spec.motion = "missing_clip.bvh";
  EXPECT_THROW(make_motion(spec, b), InputError);
  spec.motion = "dance";
  EXPECT_THROW(make_motion(spec, b), InputError);
}

}  // namespace
}  // namespace layers::motion
