// `layers body` end to end on the shared MPFB2 body and CMU clips: writes a
// valid LAYERS-H5 body sequence, exports it, and rejects bad input.
#include <gtest/gtest.h>

#include <filesystem>

#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

TEST(CliBody, ProceduralWalkToShardValidatesAndExports) {
  test::TempDir dir;
  std::string out = dir.file("walk/body.h5");
  auto r =
      run_command(test::layers_bin() + " body --shape gender=0.2,height=0.6 --motion procedural:walk --frames 24 " +
                  "--transition 6 --seed 3 --out " + out + " --export obj");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("24 frames of procedural:walk"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("13380 body vertices, 31 joints"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("exported 24 files"), std::string::npos) << r.output;
  auto v = run_command(test::layers_bin() + " validate " + out);
  EXPECT_EQ(v.exit_code, 0) << v.output;
  EXPECT_TRUE(fs::exists(dir.file("walk/body_export/body-0000_body_0023.obj")));
}

TEST(CliBody, BvhClipToDatasetFolder) {
  test::TempDir dir;
  auto r = run_command(test::layers_bin() + " body --motion cmu/131_02_start_walk_stop.bvh --frames 20 --out " +
                       dir.file("ds"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("self-intersection:"), std::string::npos) << r.output;
  auto info = run_command(test::layers_bin() + " info " + dir.file("ds"));
  EXPECT_EQ(info.exit_code, 0) << info.output;
  EXPECT_NE(info.output.find("train=1"), std::string::npos) << info.output;
  // After the blend from the T-pose the clip's subject stands with the
  // thighs close together: room between them turns the legs, and says
  // how far (to the limit, 0.15 rad).
  auto roomy = run_command(test::layers_bin() + " body --motion cmu/131_02_start_walk_stop.bvh --frames 20 " +
                           "--thigh-room 30 --out " + dir.file("roomy.h5"));
  ASSERT_EQ(roomy.exit_code, 0) << roomy.output;
  EXPECT_NE(roomy.output.find("thigh room 30 mm: legs turned in "), std::string::npos) << roomy.output;
  EXPECT_NE(roomy.output.find("of 20 frames, by up to 0.15 rad"), std::string::npos) << roomy.output;
}

TEST(CliBody, BadInputNamesTheProblem) {
  test::TempDir dir;
  auto shape = run_command(test::layers_bin() + " body --shape weight=1.5 --out " + dir.file("x.h5"));
  EXPECT_EQ(shape.exit_code, 1);
  EXPECT_NE(shape.output.find("body.shape.weight: expected a number in [0, 1], got '1.5'"), std::string::npos)
      << shape.output;
  auto kind = run_command(test::layers_bin() + " body --motion procedural:moonwalk --out " + dir.file("x.h5"));
  EXPECT_EQ(kind.exit_code, 1);
  EXPECT_NE(kind.output.find("moonwalk"), std::string::npos) << kind.output;
  std::string bvh = dir.write("broken.bvh", "HIERARCHY\nROOT Hips\n{\n  OFFSET 0 0 0\n  CHANNELS 3 Xposition\n}\n");
  auto broken = run_command(test::layers_bin() + " body --motion " + bvh + " --out " + dir.file("x.h5"));
  EXPECT_EQ(broken.exit_code, 1);
  EXPECT_NE(broken.output.find("broken.bvh: line 5"), std::string::npos) << broken.output;
  EXPECT_FALSE(fs::exists(dir.file("x.h5")));
  // Flags are named as flags (usage, exit 2), not as the config keys behind them.
  auto transition = run_command(test::layers_bin() + " body --frames 3 --transition 15 --out " + dir.file("x.h5"));
  EXPECT_EQ(transition.exit_code, 2) << transition.output;
  EXPECT_NE(transition.output.find("--transition: expected fewer frames than --frames (3), got 15"), std::string::npos)
      << transition.output;
  // Frame counts are bounded before anything is made (10^8 frames ran out
  // of memory; 2 x 10^5 ran on for hours).
  for (const char* flag : {"--frames 100000000", "--frames 200000", "--transition 100001"}) {
    auto huge = run_command(test::layers_bin() + " body " + flag + " --out " + dir.file("x.h5"));
    EXPECT_EQ(huge.exit_code, 2) << flag << ": " << huge.output;
    EXPECT_NE(huge.output.find("not in range 0 to 100000"), std::string::npos) << flag << ": " << huge.output;
  }
  auto room = run_command(test::layers_bin() + " body --thigh-room 150 --out " + dir.file("x.h5"));
  EXPECT_EQ(room.exit_code, 1) << room.output;
  EXPECT_NE(room.output.find("--thigh-room: body.thigh_room_mm: expected a number in [0, 100]"), std::string::npos)
      << room.output;
  auto missing = run_command(test::layers_bin() + " info " + dir.file("no-such-dataset"));
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find(dir.file("no-such-dataset") +
                                ": expected an existing dataset folder or HDF5 file, got nothing "
                                "(no such file or folder)"),
            std::string::npos)
      << missing.output;
}
