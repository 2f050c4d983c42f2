// `layers generate` end to end on a very small config: shards, resume,
// determinism, the dataset files, and config mismatch on resume. The
// validation thresholds are opened wide here: these tests are about the
// pipeline; the physics checks live in the sim and generator tests.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

std::string generate(const std::string& out, const std::string& extra = "") {
  return test::layers_bin() + " generate --config " + test::source_dir() + "/configs/data/tiny.yaml --out " + out +
         " --quiet --set sequences=3 --set frames=6 --set drape_frames=3 --set body.transition_frames=3"
         " --set sequences_per_shard=2 --set garments.fit.edge_length=0.08"
         " --set sim.validation.max_l_penetration=1 --set sim.validation.max_h_penetration=1"
         " --set sim.validation.max_stretch=100 " +
         extra;
}

std::string bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

}  // namespace

TEST(CliGenerate, ShardsThenCompleteDatasetThatValidates) {
  test::TempDir dir;
  const std::string out = dir.file("ds");
  auto first = run_command(generate(out, "--shard 1/2"));
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("1 scenes in shard 1/2: 1 simulated now"), std::string::npos) << first.output;
  EXPECT_NE(first.output.find("dataset not complete yet"), std::string::npos) << first.output;
  EXPECT_TRUE(fs::exists(out + "/shard-00001.h5"));
  EXPECT_FALSE(fs::exists(out + "/dataset.yaml"));

  auto second = run_command(generate(out, "--shard 0/2 --threads 2"));
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("2 scenes in shard 0/2: 2 simulated now"), std::string::npos) << second.output;
  EXPECT_NE(second.output.find("dataset complete"), std::string::npos) << second.output;
  for (const char* f : {"dataset.yaml", "splits.yaml", "stats.h5", "generator.yaml", "shard-00000.h5"})
    EXPECT_TRUE(fs::exists(out + "/" + f)) << f;
  EXPECT_FALSE(fs::exists(out + "/parts"));

  auto valid = run_command(test::layers_bin() + " validate " + out);
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
  auto info = run_command(test::layers_bin() + " info " + out);
  EXPECT_NE(info.output.find("sequences 3  frames 18"), std::string::npos) << info.output;
  const std::string splits = bytes(out + "/splits.yaml");
  for (const char* key : {"train:", "val:", "test:", "T:", "T+W:", "L:", "L+W:"})
    EXPECT_NE(splits.find(key), std::string::npos) << key << " in " << splits;

  // The validation measures recomputed from the stored frames: one line per
  // sequence and the totals; the exit code follows the count over the
  // (default) thresholds.
  auto physics = run_command(test::layers_bin() + " validate --physics " + out);
  EXPECT_NE(physics.output.find("3 sequences, 18 frames: mean H-penetration"), std::string::npos) << physics.output;
  EXPECT_NE(physics.output.find("0 non-finite values"), std::string::npos) << physics.output;
  for (const char* id : {"seq-000000", "seq-000001", "seq-000002"})
    EXPECT_NE(physics.output.find(id), std::string::npos) << id;
  const bool clean = physics.output.find("; 0 over the thresholds") != std::string::npos;
  EXPECT_EQ(physics.exit_code, clean ? 0 : 1) << physics.output;
}

TEST(CliGenerate, SameSeedSameBytesAndResumeRedoesOnlyWhatIsMissing) {
  test::TempDir dir;
  auto a = run_command(generate(dir.file("a")));
  ASSERT_EQ(a.exit_code, 0) << a.output;
  auto b = run_command(generate(dir.file("b"), "--threads 2"));
  ASSERT_EQ(b.exit_code, 0) << b.output;
  for (const char* f : {"shard-00000.h5", "shard-00001.h5", "stats.h5", "splits.yaml", "dataset.yaml"})
    EXPECT_EQ(bytes(dir.file(std::string("a/") + f)), bytes(dir.file(std::string("b/") + f))) << f;

  // A finished dataset is kept; a removed shard is made again, identically.
  auto again = run_command(generate(dir.file("a")));
  EXPECT_NE(again.output.find("0 simulated now (0 written, 0 skipped), 3 finished before"), std::string::npos)
      << again.output;
  const std::string shard1 = bytes(dir.file("a/shard-00001.h5"));
  fs::remove(dir.file("a/shard-00001.h5"));
  auto resumed = run_command(generate(dir.file("a")));
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("1 simulated now"), std::string::npos) << resumed.output;
  EXPECT_EQ(bytes(dir.file("a/shard-00001.h5")), shard1);
}

TEST(CliGenerate, BadConfigAndMismatchedResume) {
  test::TempDir dir;
  auto ok = run_command(generate(dir.file("ds")));
  ASSERT_EQ(ok.exit_code, 0) << ok.output;
  auto other = run_command(generate(dir.file("ds"), "--set seed=99"));
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("different generator config"), std::string::npos) << other.output;

  auto outfit = run_command(generate(dir.file("x"), "--set 'garments.outfits=[{inner: [jacket]}]'"));
  EXPECT_EQ(outfit.exit_code, 1) << outfit.output;
  EXPECT_NE(outfit.output.find("garments.outfits[0].inner"), std::string::npos) << outfit.output;
  auto shard = run_command(generate(dir.file("x"), "--shard 2/2"));
  EXPECT_EQ(shard.exit_code, 1) << shard.output;
  EXPECT_NE(shard.output.find("--shard"), std::string::npos) << shard.output;
  auto unknown = run_command(generate(dir.file("x"), "--set sim.substep=3"));
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("sim.substep"), std::string::npos) << unknown.output;
}

// `layers run` makes its dataset with the generator when the folder is
// missing, finds it complete the second time (the generator's own
// completeness check), and refuses a folder made with other settings.
TEST(CliRun, StudyGeneratesItsDatasetOnceThenReusesIt) {
  test::TempDir dir;
  const std::string src = test::source_dir();
  const std::string study = dir.write(
      "study.yaml",
      "name: st\noutput: " + dir.file("runs") + "\ndataset:\n  config: " + src +
          "/configs/data/tiny.yaml\n  folder: " + dir.file("data") +
          "\n  set: [sequences=3, frames=4, drape_frames=2, body.transition_frames=2, sequences_per_shard=3,"
          " garments.fit.edge_length=0.1, sim.validation.max_l_penetration=1, sim.validation.max_h_penetration=1,"
          " sim.validation.max_stretch=100]\nsteps: [train, eval]\nexperiments:\n  - {name: static, file: " +
          src + "/configs/experiments/static_tiny.yaml}\n");
  auto first = run_command(test::layers_bin() + " run " + study);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  EXPECT_NE(first.output.find("3 scenes simulated (3 written, 0 skipped)"), std::string::npos) << first.output;
  EXPECT_TRUE(fs::exists(dir.file("runs/static/eval-test/metrics.json")));
  auto second = run_command(test::layers_bin() + " run " + study);
  ASSERT_EQ(second.exit_code, 0) << second.output;
  EXPECT_NE(second.output.find("0 steps ran"), std::string::npos) << second.output;
  auto other = run_command(test::layers_bin() + " run " + study + " --set \"dataset.set=[sequences=3, frames=5]\"");
  EXPECT_EQ(other.exit_code, 1) << other.output;
  EXPECT_NE(other.output.find("made with another generator config"), std::string::npos) << other.output;
}
