// A garment as Blender hands it to a user (registered only where CMake
// found `blender`; otherwise ctest reports cli_own_garment_blender as
// skipped): one of our templates written by `layers tpose`, imported into
// Blender and exported again as OBJ and as GLB
// (scripts/blender/garment_roundtrip.py). Both read back (libs/import,
// seams welded) as the template's vertices within 1e-5 m, and the scene
// simulated with Blender's OBJ as its dress moves as the native scene
// does (the generator regression's speed tolerance). Skipped when
// Blender's Python has no numpy (its glTF exporter needs it).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "coarse_scene.h"
#include "garment_motion.h"
#include "layers/data/dataset.h"
#include "layers/geometry/nearest.h"
#include "layers/import/mesh_import.h"
#include "run_command.h"
#include "temp_dir.h"
#include "test_paths.h"

using namespace layers;

namespace {

TEST(CliOwnGarmentBlender, BlenderExportsReadBackAsTheTemplate) {
  test::TempDir dir("own-garment-blender");
  const std::string t = dir.file("tpose");
  auto r = test::run_command(test::layers_bin() + " tpose" +
                             test::coarse_scene_settings("[{inner: [dress], outer: none}]") + " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_command(std::string(LAYERS_TEST_BLENDER) + " -b --python-exit-code 1 --python " + test::source_dir() +
                        "/scripts/blender/garment_roundtrip.py -- " + t + "/dress.obj " + dir.path());
  if (r.exit_code == 77) GTEST_SKIP() << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;

  const import::ImportedMesh native = import::import_mesh(t + "/dress.obj");
  const geometry::PointIndex index(native.mesh.vertices);
  for (const char* file : {"blender.obj", "blender.glb"}) {
    const import::ImportedMesh m = import::import_mesh(dir.file(file));
    ASSERT_EQ(m.mesh.vertices.rows(), native.mesh.vertices.rows()) << file << ": seams welded back";
    EXPECT_EQ(m.mesh.faces.rows(), native.mesh.faces.rows()) << file;
    EXPECT_FALSE(m.uv.empty()) << file << ": the template's UVs";
    double worst = 0;
    for (Eigen::Index i = 0; i < m.mesh.vertices.rows(); ++i)
      worst = std::max<double>(worst, index.nearest(m.mesh.vertices.row(i)).distance);
    EXPECT_LT(worst, 1e-5) << file;
  }

  // Blender's OBJ as the dress: simulated like the template itself.
  r = test::run_command(
      test::layers_bin() + " animate" +
      test::coarse_scene_settings("[{inner: [\"file:" + dir.file("blender.obj") + "\"], outer: none}]") + " --out " +
      dir.file("own"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_command(test::layers_bin() + " animate" +
                        test::coarse_scene_settings("[{inner: [dress], outer: none}]") + " --out " +
                        dir.file("native"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // Mean speed of the dress over the one scene of each dataset.
  const auto speed_mm = [](const std::string& dataset) {
    const data::Dataset ds = data::Dataset::open(dataset);
    const data::SequenceData s = ds.read_sequence(ds.ids().front());
    return test::garment_speed_mm(s.garments.at(0), s.n_frames);
  };
  const double own = speed_mm(dir.file("own/data")), ref = speed_mm(dir.file("native/data"));
  EXPECT_LE(std::abs(own - ref), 0.02 + 0.03 * ref) << own << " against " << ref << " mm per frame";
}

}  // namespace
