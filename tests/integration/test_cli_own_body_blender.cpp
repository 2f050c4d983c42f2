// Our body with a BVH motion as Blender hands it back to a user
// (registered only where CMake found `blender`; otherwise ctest reports
// cli_own_body_blender as skipped): `layers tpose` writes the scene's body
// as a rig (body.glb: bound in its rest pose, the T-pose, then the clip),
// Blender imports it and exports it again as glTF and as FBX
// (scripts/blender/body_roundtrip.py). Read back (libs/import; the FBX in
// Blender's centimetres, with its scale), every body vertex in every frame
// is within 1e-5 m of the native one (Blender's vertex order matched by
// the rest positions), and the scene simulated on
// Blender's rig with the garments `layers tpose` wrote stores that body in
// every frame within 1e-5 m of the scene on our body. (How the garments
// then move is compared in OwnBody.TheTposeRigReadBackSimulatesAsTheNativeScene:
// the simulator is chaotic at the level of one float ulp of body motion.)
// Skipped when Blender's Python has no numpy (its glTF add-on needs it).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "coarse_scene.h"
#include "garment_motion.h"
#include "imported_skinning.h"
#include "layers/data/dataset.h"
#include "layers/geometry/nearest.h"
#include "layers/import/body_import.h"
#include "run_command.h"
#include "temp_dir.h"
#include "test_paths.h"

using namespace layers;

namespace {

TEST(CliOwnBodyBlender, BlendersRigReadsBackAsOurBodyAndDrivesTheScene) {
  test::TempDir dir("own-body-blender");
  const std::string t = dir.file("tpose");
  const std::string clip = " --set 'body.motions=[bvh:cmu/131_01_start_walk_stop.bvh]'";
  const std::string templates = test::coarse_scene_settings("[{inner: [dress], outer: jacket}]") + clip;
  auto r = test::run_command(test::layers_bin() + " tpose" + templates + " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_command(std::string(LAYERS_TEST_BLENDER) + " -b --python-exit-code 1 --python " + test::source_dir() +
                        "/scripts/blender/body_roundtrip.py -- " + t + "/body.glb " + dir.path());
  if (r.exit_code == 77) GTEST_SKIP() << r.output;
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // Every frame of Blender's rig (as glTF, and as FBX) against ours, vertex by vertex.
  const import::ImportedBody ours = import::import_rigged_body(t + "/body.glb");
  const geometry::PointIndex index(ours.rest.vertices);
  // Blender's FBX is in centimetres (the body check refuses it without its scale).
  for (const auto& [file, scale] :
       {std::pair<std::string, double>{"blender_body.glb", 1.0}, {"blender_body.fbx", 0.01}}) {
    const import::ImportedBody b = import::import_rigged_body(dir.file(file), scale);
    ASSERT_EQ(b.rest.vertices.rows(), ours.rest.vertices.rows()) << file << ": vertices split by Blender welded back";
    ASSERT_EQ(b.num_frames(), ours.num_frames()) << file;
    double rest = 0, worst = 0;
    for (Eigen::Index v = 0; v < b.rest.vertices.rows(); ++v) {
      const auto near = index.nearest(b.rest.vertices.row(v));
      rest = std::max<double>(rest, near.distance);
      for (int f = 0; f < ours.num_frames(); ++f)
        worst = std::max(worst, (test::skinned_vertex(b, f, v) - test::skinned_vertex(ours, f, near.index)).norm());
    }
    EXPECT_LT(rest, 1e-5) << file << ": the rest pose";
    EXPECT_LT(worst, 1e-5) << file << ": over " << ours.num_frames() << " frames";
    std::printf("%s: rest within %.2g m, every frame within %.2g m\n", file.c_str(), rest, worst);
  }
  const import::ImportedBody blender = import::import_rigged_body(dir.file("blender_body.glb"));

  // The scene on Blender's rig against the scene on our body, the same garment files.
  const std::string files = "[{inner: [\"file:" + t + "/dress.obj\"], outer: \"file:" + t + "/jacket.obj\"}]";
  dir.write("tpose/jacket.yaml", "self_contact: false\n");
  r = test::run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) + clip + " --out " +
                        dir.file("ours"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  r = test::run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) +
                        " --set 'body.motions=[animation]' --set 'body.own={file: \"" + dir.file("blender_body.glb") +
                        "\", garment_pose: first_frame}' --out " + dir.file("own"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const data::Dataset a_ds = data::Dataset::open(dir.file("ours/data")),
                      b_ds = data::Dataset::open(dir.file("own/data"));
  const data::SequenceData a = a_ds.read_sequence(a_ds.ids().front()), b = b_ds.read_sequence(b_ds.ids().front());
  ASSERT_EQ(a.n_frames, b.n_frames);
  const std::size_t nv = static_cast<std::size_t>(ours.rest.vertices.rows());
  geometry::Points stored(static_cast<Eigen::Index>(nv), 3);
  std::copy(a.body.positions.begin(), a.body.positions.begin() + static_cast<std::ptrdiff_t>(nv * 3), stored.data());
  double body = 0;
  for (Eigen::Index v = 0; v < blender.rest.vertices.rows(); ++v) {
    const int native = index.nearest(blender.rest.vertices.row(v)).index;
    for (std::int64_t f = 0; f < a.n_frames; ++f)
      for (int k = 0; k < 3; ++k)
        body = std::max<double>(
            body, std::abs(b.body.positions[(f * nv + v) * 3 + k] - a.body.positions[(f * nv + native) * 3 + k]));
  }
  EXPECT_LT(body, 1e-5) << "the stored body, every frame";
  ASSERT_EQ(b.garments.size(), 2u);
  for (std::size_t g = 0; g < 2; ++g)
    std::printf("%s: body within %.2g m; garment speed %.3f / %.3f mm per frame\n", a.garments[g].name.c_str(), body,
                test::garment_speed_mm(a.garments[g], a.n_frames), test::garment_speed_mm(b.garments[g], b.n_frames));
}

}  // namespace
