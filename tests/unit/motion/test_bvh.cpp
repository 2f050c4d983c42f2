// BVH reading: hierarchy, channel and rotation orders, End Sites,
// resampling, and errors naming the line for malformed files.
#include <gtest/gtest.h>

#include <sstream>

#include "body_fixture.h"
#include "layers/core/error.h"
#include "layers/motion/bvh.h"
#include "temp_dir.h"

namespace layers::motion {
namespace {

// Root with 6 channels (rotation order Z X Y), a child with Y X Z order and
// an End Site, a second child with position channels.
const char* kSmall = R"(HIERARCHY
ROOT Pelvis
{
  OFFSET 0 0 0
  CHANNELS 6 Xposition Yposition Zposition Zrotation Xrotation Yrotation
  JOINT Thigh
  {
    OFFSET 0.1 -0.1 0
    CHANNELS 3 Yrotation Xrotation Zrotation
    End Site
    {
      OFFSET 0 -0.4 0
    }
  }
  JOINT Slider
  {
    OFFSET 0 0.2 0
    CHANNELS 4 Xposition Zrotation Yrotation Xrotation
    End Site
    {
      OFFSET 0 0.1 0
    }
  }
}
MOTION
Frames: 3
Frame Time: 0.1
1 2 3 90 0 0 0 0 0 0 0 0 0
2 2 3 0 90 0 0 90 0 0.5 0 0 0
3 2 3 0 0 0 0 0 0 0 0 0 0
)";

BvhClip parse(const std::string& text) {
  std::istringstream in(text);
  return parse_bvh(in, "test.bvh");
}

// Replaces the first occurrence of `from` in the small file.
std::string edited(const std::string& from, const std::string& to) {
  std::string s = kSmall;
  const auto at = s.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return s.replace(at, from.size(), to);
}

void expect_error_at_line(const std::string& text, int line, const std::string& fragment) {
  try {
    parse(text);
    FAIL() << "expected an error mentioning line " << line;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("test.bvh"), std::string::npos) << msg;
    EXPECT_NE(msg.find("line " + std::to_string(line)), std::string::npos) << msg;
    EXPECT_NE(msg.find(fragment), std::string::npos) << msg;
  }
}

TEST(Bvh, ReadsHierarchyChannelsAndFrames) {
  const BvhClip c = parse(kSmall);
  ASSERT_EQ(c.num_joints(), 3);
  ASSERT_EQ(c.num_frames(), 3);
  EXPECT_DOUBLE_EQ(c.frame_time, 0.1);
  EXPECT_EQ(c.joints[1].name, "Thigh");
  EXPECT_EQ(c.joints[1].parent, 0);
  EXPECT_EQ(c.joints[2].parent, 0);
  EXPECT_TRUE(c.joints[1].has_end_site);
  EXPECT_EQ(c.joints[2].first_channel, 9);
  EXPECT_NEAR((c.translation[0][0] - body::Vec3(1, 2, 3)).norm(), 0.0, 1e-12);
  // Frame 0: root Zrotation 90 degrees.
  EXPECT_NEAR(body::angle_of(c.rotation[0][0].conjugate() * body::rot_z(M_PI / 2)), 0.0, 1e-9);
  // Frame 1: root "Z X Y" = (0, 90, 0) -> Rx(90); child "Y X Z" = (0, 90, 0) -> Rx(90).
  EXPECT_NEAR(body::angle_of(c.rotation[1][0].conjugate() * body::rot_x(M_PI / 2)), 0.0, 1e-9);
  EXPECT_NEAR(body::angle_of(c.rotation[1][1].conjugate() * body::rot_x(M_PI / 2)), 0.0, 1e-9);
  // Position channel on a non-root joint adds to its offset.
  EXPECT_NEAR((c.translation[1][2] - body::Vec3(0.5, 0.2, 0)).norm(), 0.0, 1e-12);
  // World positions: at frame 0 the root turned 90 degrees about z moves the thigh.
  const BvhWorld w = bvh_world(c, 0);
  EXPECT_NEAR((w.position[1] - (body::Vec3(1, 2, 3) + body::rot_z(M_PI / 2) * body::Vec3(0.1, -0.1, 0))).norm(), 0.0,
              1e-9);
}

TEST(Bvh, RotationOrderMatters) {
  // The root's channels are listed Z X Y: the rotation is Rz Rx Ry.
  const BvhClip c = parse(edited("1 2 3 90 0 0", "1 2 3 30 40 50"));
  const double a[3] = {30 * M_PI / 180, 40 * M_PI / 180, 50 * M_PI / 180};
  EXPECT_NEAR(body::angle_of(c.rotation[0][0].conjugate() * body::euler("ZXY", a)), 0.0, 1e-9);
  EXPECT_GT(body::angle_of(c.rotation[0][0].conjugate() * body::euler("ZYX", a)), 0.01);
}

TEST(Bvh, MissingMotionBlockNamesTheLine) {
  std::string s = kSmall;
  s = s.substr(0, s.find("MOTION"));
  expect_error_at_line(s, 24, "MOTION");
  expect_error_at_line(edited("MOTION", "MOTON"), 25, "MOTION");
}

TEST(Bvh, WrongChannelCountNamesTheLine) {
  // CHANNELS says 3 but names two channels.
  expect_error_at_line(edited("CHANNELS 3 Yrotation Xrotation Zrotation", "CHANNELS 3 Yrotation Xrotation"), 9,
                       "channel names");
  // A frame with one value too few.
  expect_error_at_line(edited("2 2 3 0 90 0 0 90 0 0.5 0 0 0", "2 2 3 0 90 0 0 90 0 0.5 0 0"), 29, "13 values");
  // An unknown channel name.
  expect_error_at_line(edited("Zrotation Xrotation Yrotation", "Zrotation Xrotation Wrotation"), 5, "Wrotation");
}

TEST(Bvh, NonNumericValuesNameTheLine) {
  expect_error_at_line(edited("3 2 3 0 0 0 0 0 0 0 0 0 0", "3 2 3 0 0 zero 0 0 0 0 0 0 0"), 30, "'zero'");
  expect_error_at_line(edited("OFFSET 0.1 -0.1 0", "OFFSET 0.1 abc 0"), 8, "'abc'");
  expect_error_at_line(edited("Frame Time: 0.1", "Frame Time: fast"), 27, "'fast'");
}

TEST(Bvh, FrameCountMismatchNamesTheLine) {
  expect_error_at_line(edited("Frames: 3", "Frames: 4"), 30, "4 frames");
  expect_error_at_line(edited("Frames: 3", "Frames: 2"), 30, "no more data");
}

// Declared sizes are bounded before anything is allocated for them, and
// the message gives the value as written, not an overflowed conversion.
TEST(Bvh, FrameCountAndFrameTimeAreBounded) {
  expect_error_at_line(edited("Frames: 3", "Frames: 1e30"), 26, "a whole frame count from 0 to 1000000, got 1e+30");
  expect_error_at_line(edited("Frames: 3", "Frames: 1000001"), 26, "got 1e+06");
  expect_error_at_line(edited("Frames: 3", "Frames: 2.5"), 26, "got 2.5");
  expect_error_at_line(edited("Frame Time: 0.1", "Frame Time: 100000"), 27,
                       "a frame time in (0.0001, 1] seconds, got 100000");
  expect_error_at_line(edited("Frame Time: 0.1", "Frame Time: 1e300"), 27, "got 1e+300");
  expect_error_at_line(edited("Frame Time: 0.1", "Frame Time: 0"), 27, "got 0");
  EXPECT_NO_THROW(parse(edited("Frame Time: 0.1", "Frame Time: 1")));
  // Values that would overflow the pose maths are refused where they stand.
  expect_error_at_line(edited("3 2 3 0 0 0 0 0 0 0 0 0 0", "3 2 3 1e300 0 0 0 0 0 0 0 0 0"), 30,
                       "a number within +-1e+06 (value 4 of frame 3), got '1e300'");
  expect_error_at_line(edited("OFFSET 0.1 -0.1 0", "OFFSET 0.1 -1e9 0"), 8, "OFFSET values within +-1e+06, got -1e+09");
}

// A hierarchy of `joints` joints with three rotation channels each and a
// MOTION header declaring `frames` frames of `frame_time` (no frame lines:
// the bounds refuse it before any is read).
std::string chain(int joints, const std::string& frames, const std::string& frame_time) {
  // A root with joints - 1 children (a chain would pass the depth bound).
  std::string s = "HIERARCHY\nROOT j0\n{\nOFFSET 0 0 0\nCHANNELS 3 Zrotation Xrotation Yrotation\n";
  for (int j = 1; j < joints; ++j)
    s += "JOINT j" + std::to_string(j) +
         "\n{\nOFFSET 0 0.1 0\nCHANNELS 3 Zrotation Xrotation Yrotation\nEnd Site\n{\nOFFSET 0 0.1 0\n}\n}\n";
  return s + "}\nMOTION\nFrames: " + frames + "\nFrame Time: " + frame_time + "\n";
}

std::string error_of(const std::string& text) {
  std::istringstream in(text);
  try {
    parse_bvh(in, "clip.bvh");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(read)";
}

// Joints, joints x frames and the clip's length are bounded before a frame
// is read, and resampling before it allocates: a small file cannot ask for
// gigabytes.
TEST(Bvh, JointsFramesAndLengthAreBoundedBeforeReading) {
  EXPECT_NE(error_of(chain(1001, "1", "0.1")).find("at most 1000 joints, got joint 1001 (j1000)"), std::string::npos)
      << error_of(chain(1001, "1", "0.1"));
  EXPECT_NE(
      error_of(chain(20, "1000000", "0.001")).find("at most 10000000 joints x frames, got 20 joints x 1e+06 frames"),
      std::string::npos)
      << error_of(chain(20, "1000000", "0.001"));
  EXPECT_NE(error_of(chain(1, "1000000", "1")).find("a clip of at most 3600 s (Frames x Frame Time), got 1e+06 s"),
            std::string::npos)
      << error_of(chain(1, "1000000", "1"));
  // Within the bounds the same header only misses its frames.
  EXPECT_NE(error_of(chain(20, "1000", "0.01")).find("1000 frames"), std::string::npos)
      << error_of(chain(20, "1000", "0.01"));
  // Resampling the 0.2 s clip to 10^8 fps would make 2 x 10^7 frames per joint.
  const BvhClip clip = parse(kSmall);
  try {
    resample(clip, 1e8);
    ADD_FAILURE() << "resampled to 1e8 fps";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("joints x frames at 1e+08 fps"), std::string::npos) << e.what();
  }
}

TEST(Bvh, DirectoryIsNotABvhFile) {
  layers::test::TempDir dir;
  try {
    read_bvh(dir.path());
    FAIL() << "a directory was read as a BVH file";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), dir.path() + ": expected a BVH file, got a directory");
  }
}

TEST(Bvh, ResamplesWithSlerpAndLerp) {
  const BvhClip c = parse(kSmall);  // 10 fps, 3 frames: 0.2 s
  const BvhClip r = resample(c, 20.0);
  ASSERT_EQ(r.num_frames(), 5);
  EXPECT_DOUBLE_EQ(r.frame_time, 0.05);
  // Halfway between frames 1 and 2: half the root translation step and half the rotation.
  EXPECT_NEAR((r.translation[3][0] - body::Vec3(2.5, 2, 3)).norm(), 0.0, 1e-12);
  EXPECT_NEAR(body::angle_of(r.rotation[3][0].conjugate() * body::rot_x(M_PI / 4)), 0.0, 1e-9);
}

TEST(Bvh, ReadsTheShippedClips) {
  for (const char* name : {"cmu/131_01_start_walk_stop.bvh", "cmu/131_02_start_walk_stop.bvh"}) {
    const BvhClip c = read_bvh(body::test::clip_path(name));
    EXPECT_EQ(c.num_joints(), 31) << name;
    EXPECT_NEAR(c.fps(), 120.0, 0.01) << name;
    const BvhClip r = resample(c, 30.0);
    EXPECT_NEAR(r.num_frames(), c.num_frames() / 4.0, 1.0) << name;
    EXPECT_GE(c.index("LeftWrist"), 0);
  }
  EXPECT_EQ(read_bvh(body::test::clip_path("cmu/131_01_start_walk_stop.bvh")).num_frames(), 995);
}

TEST(Bvh, MissingFileIsAnInputError) { EXPECT_THROW(read_bvh("/nonexistent/clip.bvh"), InputError); }

}  // namespace
}  // namespace layers::motion
