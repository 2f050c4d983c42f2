// A user's own body and a trained model through the CLI: `layers tpose`
// writes the scene's body as a rig (body.glb), which `layers animate`
// reads back as body.own with the garment files tpose wrote; with no
// outfit tpose writes that body alone, which animate refuses; a template
// outfit or a body in centimetres on body.own is one line, exit 1; our
// body's frames exported as a .pc2 drive a scene as a vertex cache; and
// `layers animate --model` rolls a trained model (the `static` reference
// model, trained on a three-scene dataset generated here) out on the
// simulated scene, exports its prediction and names the garment files the
// model never saw.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "coarse_scene.h"
#include "layers/data/dataset.h"
#include "run_command.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

TEST(CliOwnBody, TheTposeRigIsABodyAndBadBodiesAreOneLine) {
  test::TempDir dir("own-body");
  const std::string t = dir.file("tpose");
  auto r = run_command(test::layers_bin() + " tpose" +
                       test::coarse_scene_settings("[{inner: [dress], outer: jacket}]") + " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("body.glb (the body's rig and"), std::string::npos) << r.output;
  const std::string files = "[{inner: [\"file:" + t + "/dress.obj\"], outer: \"file:" + t + "/jacket.obj\"}]";
  const std::string own =
      " --set 'body.motions=[animation]' --set 'body.own={file: \"" + t + "/body.glb\", garment_pose: first_frame}'";
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) + own + " --out " +
                  dir.file("anim"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const data::Dataset ds = data::Dataset::open(dir.file("anim/data"));
  const data::SequenceInfo& info = ds.info(ds.ids().front());
  EXPECT_EQ(info.motion, "animation:body.glb#motion");
  EXPECT_TRUE(fs::exists(dir.file("anim/glb/seq-000000.glb")));
  // Templates on a user's body, and a body file in centimetres: one line, exit 1.
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings("[{inner: [dress], outer: jacket}]") +
                  own + " --out " + dir.file("templates"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("garments.outfits[0]: expected garment files (file:<mesh>) with body.own"), std::string::npos)
      << r.output;
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) + own +
                  " --set body.own.scale=100 --out " + dir.file("cm"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("body.glb: height: expected a body 0.5-2.5 m tall along y"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("terminate"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("cm/data")));
  // The body alone (no outfit): tpose writes its rest mesh to model
  // garments around; animate refuses it in one line.
  r = run_command(test::layers_bin() + " tpose" + test::coarse_scene_settings("[]") + own + " --out " +
                  dir.file("rest"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  std::vector<std::string> written;
  for (const auto& e : fs::directory_iterator(dir.file("rest"))) written.push_back(e.path().filename().string());
  std::sort(written.begin(), written.end());
  EXPECT_EQ(written, (std::vector<std::string>{"body.glb", "body.obj"}));
  const auto vertex_lines = [](const std::string& path) {
    std::ifstream in(path);
    int n = 0;
    for (std::string line; std::getline(in, line);) n += line.rfind("v ", 0) == 0;
    return n;
  };
  EXPECT_GT(vertex_lines(dir.file("rest/body.obj")), 1000);
  EXPECT_EQ(vertex_lines(dir.file("rest/body.obj")), vertex_lines(t + "/body.obj"));
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings("[]") + own + " --out " +
                  dir.file("bare"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("garments.outfits: expected at least one outfit to simulate"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("bare/data")));
}

TEST(CliOwnBody, AnimateWithAModelExportsItsPredictionAndNamesWhatItNeverSaw) {
  test::TempDir dir("own-body");
  const std::string t = dir.file("tpose");
  const std::string templates = test::coarse_scene_settings("[{inner: [dress], outer: jacket}]");
  auto r = run_command(test::layers_bin() + " tpose" + templates + " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // A dataset of three template scenes (train, val, test), and the static model trained on it.
  r = run_command(test::layers_bin() +
                  " generate --quiet --set sequences=3 --set splits.val=0.34 --set splits.test=0.34" + templates +
                  " --out " + dir.file("train_data"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string experiment = dir.write(
      "static.yaml", "include: [" + test::source_dir() + "/configs/models/static.yaml, " + test::source_dir() +
                         "/configs/experiments/tiny.yaml]\ndata: {dataset: " + dir.file("train_data") +
                         "}\nrun: {output: " + dir.file("run") + "}\n");
  r = run_command(test::layers_bin() + " train " + experiment + " --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;

  // Garment files the model never saw: named, and the prediction exported.
  const std::string files = "[{inner: [\"file:" + t + "/dress.obj\"], outer: \"file:" + t + "/jacket.obj\"}]";
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) + " --model " + experiment +
                  " --format obj --out " + dir.file("anim"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("note: the model never saw the garment file " + t + "/dress.obj in training"),
            std::string::npos)
      << r.output;
  EXPECT_TRUE(std::regex_search(r.output, std::regex("static: [0-9]+ frames predicted, error [0-9.]+ mm "
                                                     "against the simulator, 0 diverged")))
      << r.output;
  const data::Dataset predicted = data::Dataset::open(dir.file("anim/model/predictions.h5"));
  const data::Dataset simulated = data::Dataset::open(dir.file("anim/data"));
  ASSERT_EQ(predicted.ids(), simulated.ids());
  EXPECT_EQ(predicted.info(predicted.ids().front()).n_frames, simulated.info(simulated.ids().front()).n_frames);
  std::ifstream metrics(dir.file("anim/model/metrics.json"));
  EXPECT_EQ(nlohmann::json::parse(metrics)["dataset"], dir.file("anim/data"));
  EXPECT_FALSE(fs::is_empty(dir.file("anim/obj")));
  // The templates it was trained on: no note.
  r = run_command(test::layers_bin() + " animate" + templates + " --model " + experiment + " --out " +
                  dir.file("seen"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(r.output.find("never saw"), std::string::npos) << r.output;
  // --checkpoint without --model, and a checkpoint that is not there: one line before any simulation.
  r = run_command(test::layers_bin() + " animate" + templates + " --checkpoint last --out " + dir.file("x"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--checkpoint: expected --model with it, got no --model"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("x")));
  r = run_command(test::layers_bin() + " animate" + templates + " --model " + experiment + " --checkpoint " +
                  dir.file("none.pt") + " --out " + dir.file("y"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--checkpoint: expected a trained model's checkpoint (layers train), got"), std::string::npos)
      << r.output;
  EXPECT_FALSE(fs::exists(dir.file("y")));
}

TEST(CliOwnBody, AVertexCacheDrivesTheSceneFrameForFrame) {
  test::TempDir dir("own-body");
  const std::string t = dir.file("tpose");
  auto r = run_command(test::layers_bin() + " tpose" +
                       test::coarse_scene_settings("[{inner: [dress], outer: jacket}]") + " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string files = "[{inner: [\"file:" + t + "/dress.obj\"], outer: \"file:" + t + "/jacket.obj\"}]";
  // Our body's recorded frames as a .pc2 (layers animate's export), with the T-pose OBJ as its rest pose.
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) + " --format pc2 --out " +
                  dir.file("ours"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string cache = dir.file("ours/pc2/seq-000000_body.pc2");
  ASSERT_TRUE(fs::exists(cache)) << r.output;
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) +
                  " --set 'body.motions=[animation]' --set 'body.own={file: \"" + cache + "\", mesh: \"" + t +
                  "/body.obj\"}' --out " + dir.file("own"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const data::Dataset a_ds = data::Dataset::open(dir.file("ours/data")),
                      b_ds = data::Dataset::open(dir.file("own/data"));
  const data::SequenceData a = a_ds.read_sequence(a_ds.ids().front()), b = b_ds.read_sequence(b_ds.ids().front());
  EXPECT_EQ(b.motion, "animation:seq-000000_body.pc2");
  EXPECT_EQ(b.body.positions, a.body.positions) << "the cache's frames, as stored";
  EXPECT_EQ(b.body.joint_names, std::vector<std::string>{"Root"});
  ASSERT_EQ(b.garments.size(), 2u);
}

}  // namespace
