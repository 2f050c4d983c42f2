// Clean windows (window_min_frames, docs/sim.md): one short coarse scene is
// simulated whole, then again with the stretch cap set just under the
// stretch of a later frame; the second run stores exactly the frames before
// that frame, bit-identical to the first run's, and dataset.yaml counts the
// scene, the cut, the frames simulated and stored and the rule that cost
// the rest. A window shorter than the minimum is skipped with one line
// naming the frame and the setting; the setting's range is checked.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <vector>

#include "error_of.h"
#include "layers/data/manifest.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"
#include "layers/sim/measures.h"
#include "temp_dir.h"
#include "tiny_scene.h"

namespace layers::generate {
namespace {

constexpr int kFrames = 8;

GeneratorConfig windowed_config() {
  GeneratorConfig c = cfg::read<GeneratorConfig>(tiny_tree({"frames=" + std::to_string(kFrames)}));
  c.window_min_frames = 3;
  return c;
}

GenerateReport generate(const GeneratorConfig& config, const std::string& out) {
  GenerateOptions options;
  options.out = out;
  options.progress = false;
  return generate_dataset(config, cfg::to_yaml(cfg::to_node(config)), options);
}

TEST(CleanWindows, KeepTheFramesBeforeTheFirstBrokenRuleAndCountThem) {
  // The whole scene, with the measures the generator takes of every frame.
  GeneratorConfig whole = windowed_config();
  std::vector<double> stretch;
  const SceneResult first =
      simulate_scene(whole, sample_scene(whole, 0), [&](const char* phase, int, const sim::Solver& solver) {
        if (std::string(phase) == "record") stretch.push_back(sim::measure_frame(solver).max_stretch);
      });
  ASSERT_TRUE(first.ok);
  ASSERT_EQ(first.cut_frame, -1);
  ASSERT_EQ(static_cast<int>(stretch.size()), kFrames);
  // A later frame (at least the minimum) whose stretch is above every
  // frame's before it: with the cap between the two, the scene is cut there.
  int cut = -1;
  double before = 0;
  for (int k = 0; k < kFrames; ++k) {
    if (k >= whole.window_min_frames && stretch[k] > before) {
      cut = k;
      break;
    }
    before = std::max(before, stretch[k]);
  }
  ASSERT_GE(cut, 0) << "no frame's stretch rises above all the frames before it";

  GeneratorConfig capped = whole;
  capped.sim.validation.max_stretch = before;
  test::TempDir dir;
  const GenerateReport report = generate(capped, dir.file("data"));
  EXPECT_EQ(report.written, 1);
  EXPECT_EQ(report.cut, 1);
  const data::SequenceData seq = data::Dataset::open(dir.file("data")).read_sequence("seq-000000");
  ASSERT_EQ(seq.n_frames, cut);
  ASSERT_EQ(seq.garments.size(), first.sequence.garments.size());
  for (std::size_t g = 0; g < seq.garments.size(); ++g) {
    const std::vector<float>& all = first.sequence.garments[g].positions;
    const std::vector<float> head(
        all.begin(), all.begin() + static_cast<std::ptrdiff_t>(cut) * first.sequence.garments[g].rest.size());
    EXPECT_EQ(seq.garments[g].positions, head) << "garment " << g;
  }
  EXPECT_EQ(seq.wind.strength.size(), static_cast<std::size_t>(cut));

  const data::DatasetManifest m = data::read_manifest(dir.file("data") + "/dataset.yaml");
  ASSERT_EQ(m.motion_families.size(), 1u);
  const data::MotionFamilyCount& c = m.motion_families.begin()->second;
  EXPECT_EQ(c.sequences, 1);
  EXPECT_EQ(c.skipped, 0);
  EXPECT_EQ(c.scenes, 1);
  EXPECT_EQ(c.cut, 1);
  EXPECT_EQ(c.frames_asked, kFrames);
  EXPECT_EQ(c.frames_simulated, cut + 1);  // the broken frame was simulated, the rest not
  EXPECT_EQ(c.frames_stored, cut);
  ASSERT_EQ(c.dropped.size(), 1u);
  EXPECT_EQ(c.dropped.at("stretch"), kFrames - cut);
  EXPECT_EQ(m.n_frames, cut);
}

TEST(CleanWindows, AWindowShorterThanTheMinimumSkipsTheScene) {
  GeneratorConfig c = windowed_config();
  c.sim.validation.max_stretch = 0;  // frame 0 breaks it
  test::TempDir dir;
  const GenerateReport report = generate(c, dir.file("data"));
  EXPECT_EQ(report.written, 0);
  ASSERT_EQ(report.skip_reasons.size(), 1u);
  EXPECT_NE(report.skip_reasons[0].find("frame 0 breaks a rule (maximum edge stretch"), std::string::npos)
      << report.skip_reasons[0];
  EXPECT_NE(report.skip_reasons[0].find("0 frames, fewer than 3 (window_min_frames)"), std::string::npos)
      << report.skip_reasons[0];
  const data::DatasetManifest m = data::read_manifest(dir.file("data") + "/dataset.yaml");
  const data::MotionFamilyCount& f = m.motion_families.begin()->second;
  EXPECT_EQ(f.skipped, 1);
  EXPECT_EQ(f.frames_simulated, 1);
  EXPECT_EQ(f.frames_stored, 0);
  EXPECT_EQ(f.dropped.at("stretch"), kFrames);
}

// A body that crosses itself beyond repair from a later frame (the CMU
// clip 02_04 with the paper's 4 mm gap) is a cut too: the frames before
// it are stored and dataset.yaml charges the rest to the body. Without
// clean windows the same scene is skipped whole.
TEST(CleanWindows, ABodyBeyondRepairCutsTheWindowThere) {
  constexpr int kAsked = 20;
  GeneratorConfig c = cfg::read<GeneratorConfig>(
      tiny_tree({"frames=" + std::to_string(kAsked), "body.motions=[cmu/library/02_04.bvh]", "body.self_gap_mm=4"}));
  c.window_min_frames = 3;
  test::TempDir dir;
  const GenerateReport report = generate(c, dir.file("data"));
  ASSERT_EQ(report.written, 1) << (report.skip_reasons.empty() ? "" : report.skip_reasons[0]);
  const data::DatasetManifest m = data::read_manifest(dir.file("data") + "/dataset.yaml");
  const data::MotionFamilyCount& f = m.motion_families.begin()->second;
  EXPECT_EQ(f.cut, 1);
  ASSERT_GE(f.frames_stored, c.window_min_frames);
  ASSERT_LT(f.frames_stored, kAsked);
  EXPECT_EQ(f.frames_simulated, f.frames_stored);  // nothing simulated past the body's last good frame
  EXPECT_EQ(f.dropped.at("body"), kAsked - f.frames_stored);
  // The body's first frame beyond repair is where the window ends.
  const SceneSimulation scene(c, sample_scene(c, 0));
  EXPECT_EQ(scene.recorded_frames(), f.frames_stored);
  EXPECT_EQ(scene.body().sequence.num_frames, c.body.transition_frames + f.frames_stored);
  // Without clean windows the whole window must be clean: skipped.
  c.window_min_frames = 0;
  test::TempDir whole;
  const GenerateReport skipped = generate(c, whole.file("data"));
  EXPECT_EQ(skipped.written, 0);
}

TEST(CleanWindows, TheMinimumIsOffOrThreeToTheRecordedFrames) {
  GeneratorConfig c = windowed_config();
  c.window_min_frames = 2;
  EXPECT_NE(test::error_of([&] { check(c, "w.yaml"); }).find("window_min_frames"), std::string::npos);
  c.window_min_frames = kFrames + 1;
  EXPECT_NE(test::error_of([&] { check(c, "w.yaml"); }).find("got 9"), std::string::npos);
  c.window_min_frames = kFrames;
  EXPECT_EQ(test::error_of([&] { check(c, "w.yaml"); }), "(no error)");
  c.window_min_frames = 0;
  EXPECT_EQ(test::error_of([&] { check(c, "w.yaml"); }), "(no error)");
}

}  // namespace
}  // namespace layers::generate
