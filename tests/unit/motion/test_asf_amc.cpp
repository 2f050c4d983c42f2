// ASF/AMC clips (issue 60 item 4) on files written inside the tests: a
// chain whose middle bone has a turned axis frame, against joint positions
// worked by hand; the skeleton found beside the motion; each refusal as
// one line naming the file and line.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/motion/asf_amc.h"
#include "layers/motion/bvh_write.h"
#include "layers/motion/retarget.h"
#include "temp_dir.h"

namespace layers::motion {
namespace {

// root -> a -> b. `a` points up z (length 2), its frame C turned 90
// degrees about z, and it turns about its own x (which C takes to the
// world's y); `b` points up z (length 1) and has no dof. Lengths are
// inches times `:units length 1`.
const char* kAsf = R"(# a test skeleton
:version 1.10
:name test
:units
  mass 1.0
  length 1
  angle deg
:documentation
  made in the test
:root
   order TX TY TZ RX RY RZ
   axis XYZ
   position 0 0 0
   orientation 0 0 0
:bonedata
  begin
     id 1
     name a
     direction 0 0 1
     length 2
     axis 0 0 90  XYZ
    dof rx
    limits (-160.0 20.0)
  end
  begin
     id 2
     name b
     direction 0 0 1
     length 1
     axis 0 0 0  XYZ
  end
:hierarchy
  begin
    root a
    a b
  end
)";

std::string message_of(const std::function<void()>& f) { return test::error_of<InputError>(f); }

TEST(AsfAmc, JointsFollowTheBonesAxisFramesAsWorkedByHand) {
  test::TempDir dir("asf_amc");
  dir.write("07.asf", kAsf);
  // Frame 1 at rest; frame 2: the root moved 10 inches along x, `a` turned
  // 90 degrees about its x.
  const std::string amc = dir.write("07_01.amc",
                                    ":FULLY-SPECIFIED\n:DEGREES\n1\nroot 0 0 0 0 0 0\na 0\n"
                                    "2\nroot 10 0 0 0 0 0\na 90\n");
  EXPECT_EQ(asf_for_amc(amc), dir.file("07.asf"));
  const BvhClip clip = read_asf_amc(amc);
  ASSERT_EQ(clip.num_joints(), 3);
  EXPECT_EQ(clip.joints[0].name, "root");
  EXPECT_EQ(clip.joints[1].name, "a");
  EXPECT_EQ(clip.joints[2].parent, 1);
  EXPECT_NEAR(clip.fps(), 120.0, 1e-9);
  ASSERT_EQ(clip.num_frames(), 2);
  const double inch = 0.0254;
  // b starts where a ends: 2 inches up a's direction.
  EXPECT_LT((clip.joints[2].offset - body::Vec3(0, 0, 2 * inch)).norm(), 1e-12);
  ASSERT_TRUE(clip.joints[2].has_end_site);
  EXPECT_LT((clip.joints[2].end_site - body::Vec3(0, 0, inch)).norm(), 1e-12);
  const BvhWorld rest = bvh_world(clip, 0);
  EXPECT_LT((rest.position[2] - body::Vec3(0, 0, 2 * inch)).norm(), 1e-12);
  // C M C^-1 with C = Rz(90), M = Rx(90): a quarter turn about the world's
  // y, which takes a's direction z to x: b's start 2 inches along x, plus
  // the root's 10 inches.
  const BvhWorld moved = bvh_world(clip, 1);
  EXPECT_LT((moved.position[0] - body::Vec3(10 * inch, 0, 0)).norm(), 1e-12);
  EXPECT_LT((moved.position[2] - body::Vec3(12 * inch, 0, 0)).norm(), 1e-9);
  EXPECT_LT(moved.rotation[1].angularDistance(body::Quat(Eigen::AngleAxisd(M_PI / 2, body::Vec3::UnitY()))), 1e-9);
  // Read by extension like a BVH file.
  EXPECT_TRUE(is_clip_file(amc));
  EXPECT_EQ(read_clip(amc).num_frames(), 2);
}

TEST(AsfAmc, CmuBoneNamesMapOntoTheRig) {
  BvhClip clip;
  clip.joints.resize(2);
  clip.joints[0].name = "root";
  clip.joints[1].name = "lfemur";
  const auto names = joint_name_map(clip);
  EXPECT_EQ(names.at("lfemur"), "LeftUpLeg");
  EXPECT_EQ(names.at("root"), "Hips");
  EXPECT_EQ(names.at("rhumerus"), "RightArm");
}

TEST(AsfAmc, DamageIsOneLineNamingFileAndLine) {
  test::TempDir dir("asf_amc");
  dir.write("07.asf", kAsf);
  std::string e = message_of([&] { read_asf_amc(dir.write("07_02.amc", ":DEGREES\n1\nroot 0 0 0 0 0 0\na 1 2\n")); });
  EXPECT_NE(e.find("07_02.amc:4: expected 1 values for 'a' (its dof in "), std::string::npos) << e;
  e = message_of([&] { read_asf_amc(dir.write("07_03.amc", ":DEGREES\n1\nroot 0 0 0 0 0 0\nc 1\n")); });
  EXPECT_NE(e.find("07_03.amc:4: expected a bone of "), std::string::npos) << e;
  e = message_of(
      [&] { read_asf_amc(dir.write("07_04.amc", ":DEGREES\n1\nroot 0 0 0 0 0 0\n2\nroot 0 0 0 0 0 0\na 0\n")); });
  EXPECT_NE(e.find("07_04.amc:2: expected a line for every moving bone in each frame, got none for 'a'"),
            std::string::npos)
      << e;
  e = message_of([&] { read_asf_amc(dir.write("07_05.amc", ":DEGREES\n1\nroot 0 0 0 0 0 nan\na 0\n")); });
  EXPECT_NE(e.find("07_05.amc:3: expected a number, got 'nan'"), std::string::npos) << e;
  std::string bad = kAsf;
  bad.replace(bad.find("a b\n"), 4, "a z\n");
  dir.write("08.asf", bad);
  e = message_of([&] { read_asf_amc(dir.write("08_01.amc", ":DEGREES\n1\nroot 0 0 0 0 0 0\na 0\n")); });
  EXPECT_NE(e.find("08.asf:35: expected bones of :bonedata as children, got 'z'"), std::string::npos) << e;
  test::TempDir lone("asf_amc_lone");
  e = message_of([&] { read_asf_amc(lone.write("walk.amc", "1\nroot 0 0 0 0 0 0\n")); });
  EXPECT_NE(e.find("walk.amc: skeleton: expected its skeleton beside it"), std::string::npos) << e;
}

// The clips shipped from ASF/AMC are written as BVH: read back, every
// joint's world position equals the clip's in every frame; a dropped
// joint takes those below it and leaves an End Site where it started.
TEST(AsfAmc, WrittenAsBvhItReadsBackTheSameMotion) {
  test::TempDir dir("asf_amc");
  dir.write("07.asf", kAsf);
  const BvhClip clip = read_asf_amc(dir.write("07_01.amc",
                                              ":DEGREES\n1\nroot 1 2 3 10 20 30\na 45\n"
                                              "2\nroot 10 0 0 -100 5 170\na -120\n"));
  write_bvh(clip, dir.file("07_01.bvh"));
  const BvhClip back = read_bvh(dir.file("07_01.bvh"));
  ASSERT_EQ(back.num_joints(), 3);
  ASSERT_EQ(back.num_frames(), 2);
  EXPECT_NEAR(back.frame_time, clip.frame_time, 1e-12);
  for (int f = 0; f < 2; ++f) {
    const BvhWorld a = bvh_world(clip, f), b = bvh_world(back, f);
    for (int j = 0; j < 3; ++j) {
      // Back in metres from the file's centimetres.
      EXPECT_LT((a.position[j] * 100 - b.position[j]).norm(), 1e-4) << f << " " << j;
      EXPECT_LT(a.rotation[j].angularDistance(b.rotation[j]), 1e-6) << f << " " << j;
    }
  }
  const BvhClip cut = without_joints(clip, {"b"});
  ASSERT_EQ(cut.num_joints(), 2);
  EXPECT_TRUE(cut.joints[1].has_end_site);
  EXPECT_LT((cut.joints[1].end_site - clip.joints[2].offset).norm(), 1e-12);
  EXPECT_EQ(cut.rotation[1].size(), 2u);
}

}  // namespace
}  // namespace layers::motion
