// A user's own garments through the CLI: `layers tpose` writes a scene's
// body and template garments in the T-pose as OBJ (and refuses to replace
// them); `layers animate` simulates those meshes named as file:<mesh>
// entries and exports a GLB; a garment moved into the body is refused with
// one line naming the file and the vertex count, exit 1, before any
// simulation; an --out used before is refused.
#include <gtest/gtest.h>

#include <filesystem>
#include <regex>

#include "coarse_scene.h"
#include "file_bytes.h"
#include "layers/data/dataset.h"
#include "layers/data/obj.h"
#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

TEST(CliOwnGarment, TposeThenAnimateTheGarmentFiles) {
  test::TempDir dir("own-garment");
  const std::string t = dir.file("tpose");
  auto r = run_command(test::layers_bin() + " tpose" +
                       test::coarse_scene_settings("[{inner: [dress], outer: jacket}]") + " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* f : {"body.obj", "dress.obj", "jacket.obj"}) EXPECT_TRUE(fs::exists(t + "/" + f)) << f;
  EXPECT_FALSE(data::read_obj(t + "/dress.obj").uv_faces.empty()) << "the template's UVs are written";
  r = run_command(test::layers_bin() + " tpose" + test::coarse_scene_settings("[{inner: [dress], outer: jacket}]") +
                  " --out " + t);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("an existing file"), std::string::npos) << r.output;

  const std::string files = "[{inner: [\"file:" + t + "/dress.obj\"], outer: \"file:" + t + "/jacket.obj\"}]";
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) + " --out " + dir.file("anim"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(fs::exists(dir.file("anim/glb/seq-000000.glb"))) << r.output;
  const data::Dataset ds = data::Dataset::open(dir.file("anim/data"));
  ASSERT_EQ(ds.ids().size(), 1u);
  const auto statics = ds.statics(ds.ids().front());
  ASSERT_EQ(statics->garments.size(), 2u);
  EXPECT_EQ(statics->garments[0].type, "imported");
  EXPECT_EQ(statics->garments[0].name, "dress");
  EXPECT_EQ(statics->garments[1].layer, 1);
  EXPECT_EQ(statics->garments[0].n_vertices(), data::read_obj(t + "/dress.obj").n_vertices());
  // Again into the same folder: refused, the first run's files kept.
  r = run_command(test::layers_bin() + " animate" + test::coarse_scene_settings(files) + " --out " + dir.file("anim"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("a folder holding data/ from an earlier run"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir.file("anim/glb/seq-000000.glb")));
}

// Issue 63 item 4: a refused scene leaves something to look at with
// --keep-refused (its frames as a shard, what broke, a GLB), and a refused
// animate does not use up its --out folder.
TEST(CliOwnGarment, ARefusedSceneIsKeptToLookAtAndDoesNotUseUpOut) {
  test::TempDir dir("own-garment");
  const std::string refuse =
      test::coarse_scene_settings("[{inner: [dress], outer: jacket}]") + " --set sim.validation.max_stretch=0";
  const std::string out = dir.file("anim");
  auto r = run_command(test::layers_bin() + " animate" + refuse + " --out " + out + " --keep-refused");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the scene was refused: seq-000000"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("are in " + out + "/refused/seq-000000.h5"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(out + "/data")) << "a refused run's data/ does not stay";
  EXPECT_TRUE(fs::exists(out + "/refused/glb/seq-000000.glb"));
  const data::Dataset kept = data::Dataset::open(out + "/refused/seq-000000.h5");
  ASSERT_EQ(kept.ids(), std::vector<std::string>{"seq-000000"});
  EXPECT_EQ(kept.info("seq-000000").n_frames, 3) << "every recorded frame (no clean windows here)";
  const std::string about = test::read_bytes(out + "/refused/seq-000000.refused.yaml");
  EXPECT_NE(about.find("rule: stretch"), std::string::npos) << about;
  EXPECT_NE(about.find("maximum edge stretch"), std::string::npos) << about;
  // Where: the most stretched edges of the worst frame, the first of them
  // as stretched as the rule's message says.
  EXPECT_NE(about.find("where_frame: "), std::string::npos) << about;
  const std::smatch said = [&] {
    std::smatch m;
    std::regex_search(about, m, std::regex("maximum edge stretch ([0-9.]+)%"));
    return m;
  }();
  ASSERT_FALSE(said.empty()) << about;
  const std::string first = about.substr(about.find("most_stretched_edges:"));
  EXPECT_NE(first.find(": edge "), std::string::npos) << about;
  EXPECT_NE(first.find("stretched " + said[1].str() + "%"), std::string::npos) << about;
  EXPECT_NE(first.find(", nearest joint "), std::string::npos) << about;
  // The same command again: the same refusal, not "a folder holding data/";
  // with --keep-refused again, refused/ is not replaced.
  r = run_command(test::layers_bin() + " animate" + refuse + " --out " + out);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("the scene was refused"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("(--keep-refused keeps its frames to look at)"), std::string::npos) << r.output;
  r = run_command(test::layers_bin() + " animate" + refuse + " --out " + out + " --keep-refused");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("--keep-refused: expected a folder without refused/"), std::string::npos) << r.output;
}

TEST(CliOwnGarment, BadFilesAreOneLineAndChangedFilesAreNotResumed) {
  test::TempDir dir("own-garment");
  const std::string t = dir.file("tpose");
  auto r = run_command(test::layers_bin() + " tpose" + test::coarse_scene_settings("[{inner: [dress], outer: none}]") +
                       " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string outfit = "[{inner: [\"file:" + t + "/dress.obj\"], outer: none}]";
  const std::string generate =
      test::layers_bin() + " generate --quiet --set sequences=1" + test::coarse_scene_settings(outfit);
  // Attributes out of their range and a mesh in centimetres: one line, exit 1, before any scene.
  dir.write("tpose/dress.yaml", "attributes: {friction: 500}\n");
  r = run_command(generate + " --out " + dir.file("a"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("dress.yaml"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("friction"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("a/generator.yaml")));
  dir.write("tpose/dress.yaml", "scale: 100\n");
  r = run_command(generate + " --out " + dir.file("a"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("dress.obj: scale: expected a garment in metres"), std::string::npos) << r.output;
  // A dataset made with the file, then the file changed: not resumed.
  fs::remove(dir.file("tpose/dress.yaml"));
  r = run_command(generate + " --out " + dir.file("b"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  dir.write("tpose/dress.yaml", "self_contact: false\n");
  r = run_command(generate + " --out " + dir.file("b"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("generator.yaml"), std::string::npos) << r.output;
}

TEST(CliOwnGarment, AGarmentInsideTheBodyIsOneLineBeforeAnySimulation) {
  test::TempDir dir("own-garment");
  const std::string t = dir.file("tpose");
  auto r = run_command(test::layers_bin() + " tpose" + test::coarse_scene_settings("[{inner: [dress], outer: none}]") +
                       " --out " + t);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  data::ObjMesh dress = data::read_obj(t + "/dress.obj");
  for (std::size_t i = 2; i < dress.positions.size(); i += 3) dress.positions[i] -= 0.08f;  // 8 cm back
  data::write_obj(dir.file("sunk.obj"), dress);
  r = run_command(test::layers_bin() + " animate" +
                  test::coarse_scene_settings("[{inner: [\"file:" + dir.file("sunk.obj") + "\"], outer: none}]") +
                  " --out " + dir.file("anim"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("sunk.obj: vertices: expected a garment outside the body in its T-pose (frame 0), got "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("vertices inside the body, most near the"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find("terminate"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir.file("anim/glb"))) << "nothing exported for a refused scene";
  // `layers tpose` of that scene writes the meshes it could make and says
  // the scene is refused, exit 1 (it was a note with exit 0; issue 62).
  r = run_command(test::layers_bin() + " tpose" +
                  test::coarse_scene_settings("[{inner: [\"file:" + dir.file("sunk.obj") + "\"], outer: none}]") +
                  " --out " + dir.file("t2"));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find(": scene 0: expected a scene that can be simulated"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sunk.obj"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir.file("t2/body.obj")));
}

}  // namespace
