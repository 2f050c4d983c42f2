// `layers crosscheck` through the real Blender (registered only when
// CMake found `blender`; otherwise ctest reports cli_crosscheck_blender as
// skipped): a tiny synthetic scene, 4 frames, both setups, in well under a
// minute.
#include <gtest/gtest.h>

#include <filesystem>

#include "layers/data/dataset_writer.h"
#include "layers/data/pc2.h"
#include "run_command.h"
#include "synthetic_sequence.h"
#include "temp_dir.h"

using namespace layers;

TEST(CliCrosscheckBlender, BothSetupsGiveATable) {
  test::TempDir dir;
  const std::string ds = dir.file("ds");
  {
    data::DatasetWriter writer(ds, data::DatasetWriterOptions{});
    data::testing::SyntheticSize size;
    size.frames = 4;
    writer.add(data::testing::make_sequence("a", 3, size));
    writer.finish();
  }
  const std::string work = dir.file("work");
  auto r = test::run_command(test::layers_bin() + " crosscheck " + ds + " a --frames 4 --blender " +
                             LAYERS_TEST_BLENDER + " --work " + work);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("| ours (stored) | Blender, merged | Blender, separate |"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| frames measured (1..n-1) | 3 | 3 | 3 |"), std::string::npos) << r.output;
  for (const char* setup : {"merged", "separate"}) {
    for (const char* mesh : {"tshirt", "jacket"}) {
      const data::Pc2Header h = data::read_pc2_header(work + "/" + setup + "/" + mesh + ".pc2");
      EXPECT_EQ(h.n_points, 128) << setup << " " << mesh;
      EXPECT_EQ(h.n_samples, 4) << setup << " " << mesh;
    }
  }
  EXPECT_TRUE(std::filesystem::exists(work + "/table.md"));
}
