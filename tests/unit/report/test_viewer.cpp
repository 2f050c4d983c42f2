// The report's viewer (viewer.h) on the tiny synthetic dataset: scene.js
// holds every shown frame's positions exactly as stored and each frame's
// metrics as the evaluation measures them; the byte budget limits the
// frames; a missing three.js is one line; report.md links the page. Where
// node, Debian's chromium-headless-shell, libjs-three and the npm tools
// (tests/browser, installed by scripts/setup.sh) are present, the page
// itself plays in the browser and draws the stored positions.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/core/error.h"
#include "layers/report/report.h"
#include "layers/report/viewer.h"
#include "predictions_fixture.h"
#include "run_command.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using testing::FakeRun;
using testing::PredictionsFixture;

std::string read_all(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

json read_scene(const std::string& report) {
  std::string text = read_all(report + "/viewer/scene.js");
  const std::string head = "window.LAYERS_SCENE = ";
  EXPECT_EQ(text.rfind(head, 0), 0u);
  text = text.substr(head.size());
  return json::parse(text.substr(0, text.rfind(';')));
}

std::vector<float> floats(const std::string& b64) {
  std::string bytes;
  unsigned v = 0;
  int bits = 0;
  for (char c : b64) {
    const std::string k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    const std::size_t d = k.find(c);
    if (d == std::string::npos) break;  // '=' padding
    v = (v << 6) | static_cast<unsigned>(d);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes.push_back(static_cast<char>((v >> bits) & 0xff));
    }
  }
  std::vector<float> out(bytes.size() / sizeof(float));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(float));
  return out;
}

std::int64_t folder_bytes(const std::string& dir) {
  std::int64_t n = 0;
  for (const auto& e : fs::directory_iterator(dir)) n += static_cast<std::int64_t>(e.file_size());
  return n;
}

// Two runs whose garments drift by 1 cm and 2 cm along x after frame 1.
struct ViewerFixture : PredictionsFixture {
  std::vector<RunResults> runs;
  ViewerOptions options;
  ViewerFixture() : PredictionsFixture("report-viewer") {
    runs = {load_run(run("near_run", FakeRun{}, 0.01f)), load_run(run("far_run", FakeRun{}, 0.02f))};
    options.three = dir.write("three.min.js", "// three.js stand-in: the scene file is what is checked here\n");
  }
};

TEST(Viewer, SceneHoldsEveryFrameAsStoredWithItsMetrics) {
  ViewerFixture f;
  std::vector<std::string> notes;
  const Viewer v = write_viewer(f.runs, PictureOptions{}, f.options, f.dir.file("report"), notes);
  EXPECT_TRUE(notes.empty()) << ::testing::PrintToString(notes);
  EXPECT_EQ(v.rows, (std::vector<std::string>{"ground truth", "near_run", "far_run"}));
  EXPECT_EQ(v.sequence, "seq-0");
  EXPECT_EQ(v.frames, 8);
  EXPECT_EQ(read_all(v.page), viewer_page());
  EXPECT_EQ(read_all(f.dir.file("report/viewer/three.min.js")), read_all(f.options.three));

  const json scene = read_scene(f.dir.file("report"));
  const data::SequenceData& truth = f.sequences[0];
  EXPECT_EQ(scene["frames"], 8);
  EXPECT_EQ(floats(scene["body"]["positions"]), truth.body.positions);
  ASSERT_EQ(scene["rows"].size(), 3u);
  const float offsets[] = {0.0f, 0.01f, 0.02f};
  for (std::size_t r = 0; r < 3; ++r) {
    const json& row = scene["rows"][r];
    EXPECT_EQ(row["truth"], r == 0);
    ASSERT_EQ(row["garments"].size(), truth.garments.size());
    for (std::size_t g = 0; g < truth.garments.size(); ++g) {
      // The prediction files' own values: the truth plus the drift, as stored.
      std::vector<float> expected = truth.garments[g].positions;
      const std::size_t per_frame = expected.size() / 8;
      for (std::size_t i = 2 * per_frame; i < expected.size(); ++i) expected[i] += offsets[r] * (i % 3 == 0);
      EXPECT_EQ(floats(row["garments"][g]), expected) << "row " << r << " garment " << g;
    }
    const json& error = row["values"]["error_mm"];
    ASSERT_EQ(error.size(), 8u);
    for (std::size_t t = 0; t < 8; ++t) {
      if (r == 0) {
        EXPECT_TRUE(error[t].is_null()) << "the ground truth has no error";
      } else {
        EXPECT_NEAR(error[t].get<double>(), t < 2 ? 0.0 : 1000.0 * offsets[r], 1e-3) << "row " << r << " frame " << t;
      }
      const json& h = row["values"]["h_collision"][t];
      ASSERT_TRUE(h.is_number()) << "row " << r << " frame " << t;
      EXPECT_GE(h.get<double>(), 0.0);
      EXPECT_LE(h.get<double>(), 1.0);
    }
  }
}

TEST(Viewer, BudgetShowsTheFirstFramesThatFit) {
  ViewerFixture f;
  std::vector<std::string> notes;
  write_viewer(f.runs, PictureOptions{}, f.options, f.dir.file("full"), notes);
  const std::int64_t full = folder_bytes(f.dir.file("full/viewer"));
  f.options.max_bytes = full * 6 / 10;
  const Viewer v = write_viewer(f.runs, PictureOptions{}, f.options, f.dir.file("part"), notes);
  EXPECT_GE(v.frames, 2);
  EXPECT_LT(v.frames, 8);
  EXPECT_LE(folder_bytes(f.dir.file("part/viewer")), f.options.max_bytes);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("shows frames 0-" + std::to_string(v.frames - 1) + " of 8"), std::string::npos) << notes[0];
  EXPECT_EQ(read_scene(f.dir.file("part"))["frames"], v.frames);

  f.options.max_bytes = 1000;
  try {
    write_viewer(f.runs, PictureOptions{}, f.options, f.dir.file("none"), notes);
    FAIL() << "a budget without room for two frames was accepted";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("not even two frames of sequence seq-0"), std::string::npos) << e.what();
  }
}

TEST(Viewer, MissingThreeIsOneLineAndTheReportSaysWhy) {
  ViewerFixture f;
  ReportInputs inputs;
  inputs.charts = false;
  inputs.viewer.three = f.dir.file("no-such/three.min.js");
  ReportResult r = write_report(f.runs, inputs, f.dir.file("report"));
  EXPECT_TRUE(r.viewer.empty());
  const std::string md = read_all(r.report);
  EXPECT_NE(md.find("No viewer: three.js not found at " + inputs.viewer.three), std::string::npos) << md;
  EXPECT_FALSE(fs::exists(f.dir.file("report/viewer")));

  inputs.viewer = f.options;
  r = write_report(f.runs, inputs, f.dir.file("report2"));
  EXPECT_EQ(r.viewer, f.dir.file("report2/viewer/index.html"));
  EXPECT_NE(read_all(r.report).find("[viewer/index.html](viewer/index.html)"), std::string::npos);

  inputs.viewer.enabled = false;
  r = write_report(f.runs, inputs, f.dir.file("report3"));
  EXPECT_NE(read_all(r.report).find("No viewer: the viewer was switched off"), std::string::npos);
  for (const std::string& p : r.problems) EXPECT_NE(p.rfind("viewer:", 0), 0u) << p;
}

// The page in Debian's headless Chromium (WebGL through SwiftShader).
TEST(Viewer, PlaysInHeadlessChromiumAndDrawsTheStoredPositions) {
  const std::string node = LAYERS_TEST_NODE, chromium = LAYERS_TEST_CHROMIUM, tools = LAYERS_TEST_BROWSER_DIR;
  if (node.empty()) GTEST_SKIP() << "node not found when CMake ran";
  if (chromium.empty()) GTEST_SKIP() << "chromium-headless-shell not found when CMake ran (Debian package)";
  if (!fs::exists(kDebianThree)) GTEST_SKIP() << kDebianThree << " missing (Debian package libjs-three)";
  if (!fs::exists(tools + "/node_modules/puppeteer-core"))
    GTEST_SKIP() << "puppeteer-core not installed in " << tools << " (scripts/setup.sh runs npm ci there)";
  ViewerFixture f;
  f.options.three = kDebianThree;
  std::vector<std::string> notes;
  const Viewer v = write_viewer(f.runs, PictureOptions{}, f.options, f.dir.file("report"), notes);
  const int frame = 5;
  const std::string out = f.dir.file("seen.json"), shot = f.dir.file("screenshot.png");
  const test::CommandResult run = test::run_command(node + " " + tools + "/viewer_check.js " + chromium + " " + v.page +
                                                    " " + std::to_string(frame) + " " + out + " " + shot);
  ASSERT_EQ(run.exit_code, 0) << run.output;
  const json seen = json::parse(read_all(out));
  EXPECT_TRUE(seen["console_errors"].empty()) << seen["console_errors"].dump();
  EXPECT_TRUE(seen["advanced"].get<bool>()) << "playing did not advance the frame";
  EXPECT_EQ(seen["shown_frame"], frame);
  EXPECT_GT(seen["drawn_share"].get<double>(), 0.02) << "the canvas is (nearly) blank";
  EXPECT_GT(fs::file_size(shot), 5000u);
  EXPECT_EQ(seen["rows"].get<std::vector<std::string>>(), v.rows);

  // Every row's meshes as drawn at `frame` equal the stored frame exactly.
  const data::SequenceData& truth = f.sequences[0];
  const float offsets[] = {0.0f, 0.01f, 0.02f};
  ASSERT_EQ(seen["positions"].size(), 3u);
  for (std::size_t r = 0; r < 3; ++r) {
    const json& meshes = seen["positions"][r];
    ASSERT_EQ(meshes.size(), 1 + truth.garments.size());
    auto frame_of = [&](const std::vector<float>& all, std::size_t vertices) {
      return std::vector<float>(all.begin() + frame * vertices * 3, all.begin() + (frame + 1) * vertices * 3);
    };
    std::vector<float> drawn;
    for (double x : meshes[0]) drawn.push_back(static_cast<float>(x));
    const std::size_t body_v = truth.body.positions.size() / 3 / 8;
    EXPECT_EQ(drawn, frame_of(truth.body.positions, body_v)) << "row " << r << " body";
    for (std::size_t g = 0; g < truth.garments.size(); ++g) {
      const std::size_t gv = truth.garments[g].positions.size() / 3 / 8;
      std::vector<float> expected = frame_of(truth.garments[g].positions, gv);
      for (std::size_t i = 0; i < expected.size(); ++i) expected[i] += offsets[r] * (i % 3 == 0);
      drawn.clear();
      for (double x : meshes[1 + g]) drawn.push_back(static_cast<float>(x));
      EXPECT_EQ(drawn, expected) << "row " << r << " garment " << g;
    }
  }
}

}  // namespace
}  // namespace layers::report
