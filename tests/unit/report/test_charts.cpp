// The whole report on two fake runs whose predictions and ground truth are
// tiny synthetic LAYERS-H5 files: every chart is drawn as a non-empty PNG
// next to its script and data, and report.md embeds them. Skipped when
// gnuplot is not installed.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/report/gnuplot.h"
#include "layers/report/report.h"
#include "predictions_fixture.h"
#include "report_fixtures.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;
using layers::test::TempDir;
using testing::FakeRun;

bool is_png(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  char sig[8] = {};
  in.read(sig, 8);
  return in && std::string(sig + 1, 3) == "PNG" && fs::file_size(path) > 1000;
}

TEST(Charts, EveryChartIsANonEmptyPng) {
  try {
    Gnuplot::find();
  } catch (const std::exception& e) {
    GTEST_SKIP() << e.what();
  }
  testing::PredictionsFixture f;
  FakeRun fast, slow;
  fast.model = "fastnet", fast.ms_per_frame = 0.5, fast.error = 30;
  slow.model = "slownet", slow.ms_per_frame = 8.0, slow.error = 6, slow.diverged_at = 3;
  slow.step_errors = {1, 2, 1000};
  ReportInputs inputs;
  inputs.runs = {f.run("fast_run", fast, 0.05f), f.run("slow_run", slow, -0.02f)};
  f.dir.write("slow_run/bench.json", testing::bench_json("slownet", 2.0, 9.0));
  // The trainer's per-epoch record (selection.json): the learning curves.
  f.dir.write("fast_run/selection.json",
              R"({"val_error_mm_by_epoch": [30.0, 25.0, 22.0], "windows_by_epoch": [100, 100, 100]})");
  f.dir.write("slow_run/selection.json",
              R"({"val_error_mm_by_epoch": [10.0, 8.0, 9.0], "windows_by_epoch": [50, 50, 50]})");
  inputs.title = "Test report";
  inputs.picture.frames = 3;
  const std::string out = f.dir.file("out");
  const ReportResult result = write_report(inputs, out);

  // The only missing piece: fast_run has no bench.json.
  ASSERT_EQ(result.problems.size(), 1u) << ::testing::PrintToString(result.problems);
  EXPECT_NE(result.problems[0].find("fast_run: no bench.json"), std::string::npos) << result.problems[0];
  const std::vector<std::string> expected = {"speed_accuracy",
                                             "by_step_error_mm",
                                             "by_step_h_collision",
                                             "by_step_l_collision",
                                             "by_step_l_collision_plain",
                                             "by_step_h_crossing",
                                             "by_step_l_crossing",
                                             "per_type",
                                             "frames",
                                             "learning_curves"};
  ASSERT_EQ(result.charts.size(), expected.size()) << ::testing::PrintToString(result.charts);
  std::ifstream md_in(result.report);
  std::stringstream md;
  md << md_in.rdbuf();
  for (const std::string& name : expected) {
    const std::string png = out + "/charts/" + name + ".png";
    EXPECT_TRUE(is_png(png)) << png;
    EXPECT_TRUE(fs::exists(out + "/charts/" + name + ".gp")) << name;
    EXPECT_NE(md.str().find("(charts/" + name + ".png)"), std::string::npos) << name;
  }
  // Data files stay next to the PNGs; no temporary file is left behind.
  EXPECT_TRUE(fs::exists(out + "/charts/speed_accuracy_bench.dat"));
  EXPECT_TRUE(fs::exists(out + "/charts/frames_0_0.dat"));
  for (const auto& entry : fs::recursive_directory_iterator(out))
    EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos) << entry.path();
  EXPECT_EQ(result.pareto_front, (std::vector<std::string>{"fast_run", "slow_run"}));
  EXPECT_NE(md.str().find("first at step 2 (frame 3, s2: non-finite prediction)"), std::string::npos);
  EXPECT_NE(md.str().find("Sequence `seq-0` at frames 2, 5, 7"), std::string::npos) << md.str();
  EXPECT_NE(md.str().find("The top row is the dataset's ground truth"), std::string::npos);
  EXPECT_NE(md.str().find("mean Euclidean error over the test sequences (mm)"), std::string::npos);
  EXPECT_NE(md.str().find("Mean over the test sequences of"), std::string::npos);
  // Learning curves: windows seen add up over epochs; a curve whose last
  // epoch is its best is still improving.
  EXPECT_NE(md.str().find("| fast_run | 3 | 300 | 30.00, 22.00 (3), 22.00 | yes: the last epoch is the best |"),
            std::string::npos)
      << md.str();
  EXPECT_NE(md.str().find("| slow_run | 3 | 150 | 10.00, 8.00 (2), 9.00 | no |"), std::string::npos) << md.str();
}

TEST(Charts, PictureWithoutGroundTruthSaysSo) {
  try {
    Gnuplot::find();
  } catch (const std::exception& e) {
    GTEST_SKIP() << e.what();
  }
  testing::PredictionsFixture f;
  FakeRun r;
  const std::string run = f.run("only_run", r, 0.01f);
  std::vector<RunResults> runs = {load_run(run)};
  runs[0].dataset = f.dir.file("moved-away");
  std::vector<std::string> notes;
  fs::create_directories(f.dir.file("charts"));
  const Chart chart = frames_picture(Gnuplot::find(), f.dir.file("charts"), runs, PictureOptions{}, notes);
  EXPECT_TRUE(is_png(f.dir.file("charts/frames.png")));
  EXPECT_NE(chart.caption.find("No ground truth"), std::string::npos);
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("moved-away not found"), std::string::npos) << notes[0];
}

}  // namespace
}  // namespace layers::report
