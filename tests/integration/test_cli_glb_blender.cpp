// `layers export --format glb` read by the real Blender (registered only
// when CMake found `blender`; otherwise ctest reports cli_glb_blender as
// skipped): a synthetic two-layer sequence exported as GLB and as OBJ
// frames, the GLB imported with Blender's glTF importer
// (scripts/blender/glb_check.py), and every vertex of every mesh at every
// frame within 1e-5 m of the OBJ's, whole and cut into chunks. Skipped when Blender's Python has no
// numpy (its importer needs it).
#include <gtest/gtest.h>

#include "layers/data/dataset_writer.h"
#include "run_command.h"
#include "synthetic_sequence.h"
#include "temp_dir.h"
#include "test_paths.h"

using namespace layers;

TEST(CliGlbBlender, BlenderPlaysTheStoredFrames) {
  test::TempDir dir;
  const std::string ds = dir.file("ds");
  {
    data::DatasetWriter writer(ds, data::DatasetWriterOptions{});
    data::testing::SyntheticSize size;
    size.frames = 6;
    writer.add(data::testing::make_sequence("a", 3, size));
    writer.finish();
  }
  for (const char* format : {"glb", "obj"}) {
    auto r = test::run_command(test::layers_bin() + " export " + ds + " a --format " + format + " --frames 1:6 --out " +
                               dir.file("out"));
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  // The same frames in chunks of 2 frames (3 chunks per mesh).
  auto chunked = test::run_command(test::layers_bin() + " export " + ds +
                                   " a --format glb --frames 1:6 --glb-chunk 2 --out " + dir.file("chunked"));
  ASSERT_EQ(chunked.exit_code, 0) << chunked.output;
  for (const std::string& glb : {dir.file("out/a.glb"), dir.file("chunked/a.glb")}) {
    auto r =
        test::run_command(std::string(LAYERS_TEST_BLENDER) + " -b --python-exit-code 1 --python " + test::source_dir() +
                          "/scripts/blender/glb_check.py -- " + glb + " " + dir.file("out/a") + " 1 5");
    if (r.exit_code == 77) GTEST_SKIP() << r.output;
    ASSERT_EQ(r.exit_code, 0) << glb << "\n" << r.output;
    EXPECT_NE(r.output.find("over 5 frames, 3 meshes"), std::string::npos) << glb << "\n" << r.output;
  }
}
