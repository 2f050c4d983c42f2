// Retargeting the shipped CMU clips onto the rig: every rig joint mapped,
// limb directions follow the BVH, bone lengths constant, feet on the
// ground in stance.
#include <gtest/gtest.h>

#include <array>
#include <functional>
#include <map>
#include <set>
#include <sstream>

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

// A clip named as MotionBuilder, Mixamo or the SFU set name joints (Hips,
// LeftUpLeg, LeftShoulder for the clavicle, LeftArm for the upper arm; no
// hip or lower-back joints, a spine joint 1 mm above the hips, a leaf
// joint with no End Site), in centimetres: a T-pose, then legs, arms and
// spine turned.
struct MbJoint {
  const char* name;
  int parent;
  double x, y, z;
};
const MbJoint kMbJoints[] = {
    {"Hips", -1, 0, 0, 0},           {"LeftUpLeg", 0, 9, 0, 0},      {"LeftLeg", 1, 0, -40, 0},
    {"LeftFoot", 2, 0, -39, 0},      {"LeftToeBase", 3, 0, -4, 14},  {"RightUpLeg", 0, -9, 0, 0},
    {"RightLeg", 5, 0, -40, 0},      {"RightFoot", 6, 0, -39, 0},    {"RightToeBase", 7, 0, -4, 14},
    {"Spine", 0, 0, 0.1, 0},         {"Spine1", 9, 0, 26, 0},        {"Neck", 10, 0, 20, 0},
    {"Head", 11, 0, 17, 0},          {"LeftShoulder", 10, 0, 20, 0}, {"LeftArm", 13, 17, 0, 0},
    {"LeftForeArm", 14, 28, 0, 0},   {"LeftHand", 15, 22, 0, 0},     {"L_Wrist_End", 16, 10, 0, 0},
    {"RightShoulder", 10, 0, 20, 0}, {"RightArm", 18, -17, 0, 0},    {"RightForeArm", 19, -28, 0, 0},
    {"RightHand", 20, -22, 0, 0},
};

std::string mb_style_bvh(const std::vector<std::map<std::string, std::array<double, 3>>>& frames) {
  const int n = static_cast<int>(std::size(kMbJoints));
  std::ostringstream out;
  out << "HIERARCHY\n";
  // Depth-first, children in table order.
  std::function<void(int, int)> write = [&](int j, int depth) {
    const std::string pad(static_cast<std::size_t>(depth), '\t');
    out << pad << (j == 0 ? "ROOT " : "JOINT ") << kMbJoints[j].name << "\n" << pad << "{\n";
    out << pad << "\tOFFSET " << kMbJoints[j].x << " " << kMbJoints[j].y << " " << kMbJoints[j].z << "\n";
    out << pad << "\tCHANNELS " << (j == 0 ? "6 Xposition Yposition Zposition " : "3 ")
        << "Zrotation Xrotation Yrotation\n";
    bool leaf = true;
    for (int c = 0; c < n; ++c)
      if (kMbJoints[c].parent == j) {
        write(c, depth + 1);
        leaf = false;
      }
    const std::string name = kMbJoints[j].name;
    if (leaf && name != "L_Wrist_End")  // the SFU files' leaf joint without an End Site
      out << pad << "\tEnd Site\n" << pad << "\t{\n" << pad << "\t\tOFFSET 0 5 0\n" << pad << "\t}\n";
    out << pad << "}\n";
  };
  write(0, 0);
  std::vector<int> order;
  std::function<void(int)> visit = [&](int j) {
    order.push_back(j);
    for (int c = 0; c < n; ++c)
      if (kMbJoints[c].parent == j) visit(c);
  };
  visit(0);
  out << "MOTION\nFrames: " << frames.size() << "\nFrame Time: 0.0333333\n";
  for (const auto& f : frames) {
    for (int j : order) {
      if (j == 0) out << "0 92 0 ";
      const auto it = f.find(kMbJoints[j].name);
      const std::array<double, 3> zxy = it == f.end() ? std::array<double, 3>{0, 0, 0} : it->second;
      out << zxy[0] << " " << zxy[1] << " " << zxy[2] << " ";
    }
    out << "\n";
  }
  return out.str();
}

TEST(Retarget, MotionBuilderStyleNamesFollowTheClip) {
  const body::Body& b = body::test::body();
  std::vector<std::map<std::string, std::array<double, 3>>> frames(6);
  frames[3] = {{"LeftUpLeg", {0, -40, 0}}, {"RightLeg", {0, 50, 0}},    {"LeftArm", {-50, 0, 20}},
               {"RightArm", {45, 0, -10}}, {"LeftForeArm", {0, 0, 60}}, {"Spine1", {0, 10, 25}},
               {"Hips", {0, 0, 30}}};
  for (int f = 4; f < 6; ++f) frames[f] = frames[3];
  std::istringstream in(mb_style_bvh(frames));
  const BvhClip clip = parse_bvh(in, "mb_style.bvh");
  RetargetOptions options;
  options.ground = false;
  const std::unique_ptr<PoseTrack> motion = retarget(clip, b, options);
  // Rig bone and the clip's segment (same names here: the rig's are
  // MotionBuilder's), in the T-pose and turned. Before the names were read
  // by the clip's style, LeftShoulder (the clavicle) drove the upper arm;
  // before the root's direction was taken through the lower back the clip
  // lacks, the pelvis turned by 90 degrees and the legs crossed.
  const std::array<const char*, 2> bones[] = {
      {"LeftArm", "LeftForeArm"},
      {"LeftForeArm", "LeftHand"},
      {"RightArm", "RightForeArm"},
      {"LeftUpLeg", "LeftLeg"},
      {"RightLeg", "RightFoot"},
      {"LeftLeg", "LeftFoot"},
      {"Spine1", "Neck"},
      // The hip and shoulder lines: the pelvis and chest face the clip's way.
      {"RightUpLeg", "LeftUpLeg"},
      {"RightArm", "LeftArm"},
  };
  for (int f : {0, 3}) {
    const body::JointTransforms t = body::forward_kinematics(b.skeleton, motion->pose(f));
    const BvhWorld w = bvh_world(clip, f);
    for (const auto& bone : bones) {
      const body::Vec3 a = t.position[b.skeleton.require(bone[1])] - t.position[b.skeleton.require(bone[0])];
      const body::Vec3 c = w.position[clip.index(bone[1])] - w.position[clip.index(bone[0])];
      EXPECT_GT(a.normalized().dot(c.normalized()), std::cos(0.05)) << bone[0] << " frame " << f;
    }
  }
}

// A clip read through the wrong name map (here: MotionBuilder names forced
// through the CMU 3dsMax map, the clavicle driving the upper arm) is
// refused with one line naming the bone, not retargeted crooked.
TEST(Retarget, AClipTheRigCannotFollowIsRefused) {
  const body::Body& b = body::test::body();
  std::istringstream in(mb_style_bvh(std::vector<std::map<std::string, std::array<double, 3>>>(3)));
  const BvhClip clip = parse_bvh(in, "mb_style.bvh");
  RetargetOptions options;
  options.names = cmu_3dsmax_names();
  try {
    retarget(clip, b, options);
    ADD_FAILURE() << "retargeted";
  } catch (const InputError& e) {
    const std::string said = e.what();
    EXPECT_NE(said.find("mb_style.bvh"), std::string::npos) << said;
    EXPECT_NE(said.find("rig bone LeftArm -> LeftForeArm"), std::string::npos) << said;
    EXPECT_NE(said.find("from the clip's LeftShoulder -> LeftForeArm"), std::string::npos) << said;
    EXPECT_EQ(said.find('\n'), std::string::npos) << said;
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
