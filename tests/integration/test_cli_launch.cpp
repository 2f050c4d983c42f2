// `layers launch` and the distributed environment end to end: 2 ranks
// train the test plugin's model on the regression fixture, one process
// resumes the run, 2 ranks evaluate it; `layers train` starts its own
// ranks (run.ranks); exit codes are forwarded; bad
// distributed variables and a missing rank are one line each, exit 1.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "layers/core/text_file.h"
#include "run_command.h"
#include "synthetic_fixture.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

std::string layers_cmd(const std::string& env = "") {
  return "env -u RANK -u WORLD_SIZE -u SLURM_NTASKS -u SLURM_PROCID " + env +
         " LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin();
}

// The lines of `text` from the first "layers: error" on (the test plugin
// folder also holds refused plugins, whose warnings come first).
std::string from_error(const std::string& text) {
  const std::size_t at = text.find("layers: error");
  return at == std::string::npos ? text : text.substr(at);
}

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (std::size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

struct CliLaunch : ::testing::Test {
  test::TempDir dir{"layers-cli-launch"};
  std::string experiment, run;
  void SetUp() override {
    const std::string data = regression::write_fixture(dir.path());
    run = dir.file("run");
    experiment = dir.write("exp.yaml",
                           "model: {name: test_constant_velocity, params: {damping: 0.6}}\n"
                           "data: {dataset: " +
                               data +
                               "}\n"
                               "train: {epochs: 1, batch_size: 2, windows_per_epoch: 8, val_horizon: 2, "
                               "val_sequences: 2}\n"
                               "eval: {horizon: 4}\n"
                               "run: {output: " +
                               run + ", threads: 1, seed: 0, dist_timeout_s: 30}\n");
  }
};

TEST_F(CliLaunch, TwoRanksTrainOneResumesTwoEvaluate) {
  auto trained = run_command(layers_cmd() + " launch --nproc 2 -- train " + experiment + " --quiet");
  ASSERT_EQ(trained.exit_code, 0) << trained.output;
  EXPECT_EQ(count(trained.output, "trained 1 epochs"), 1) << trained.output;  // rank 0 alone prints
  EXPECT_NE(trained.output.find("frames/s  "), std::string::npos) << trained.output;
  EXPECT_NE(trained.output.find(" on 2 ranks, "), std::string::npos) << trained.output;
  EXPECT_TRUE(fs::exists(run + "/checkpoint-last.pt"));

  auto resumed = run_command(layers_cmd() + " train " + experiment + " --resume --quiet --set train.epochs=2");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("trained 2 epochs"), std::string::npos) << resumed.output;
  EXPECT_EQ(resumed.output.find(" ranks, "), std::string::npos) << resumed.output;

  auto evaluated = run_command(layers_cmd() + " launch --nproc 2 -- eval " + experiment + " --quiet");
  ASSERT_EQ(evaluated.exit_code, 0) << evaluated.output;
  EXPECT_EQ(count(evaluated.output, "overall"), 1) << evaluated.output;
  EXPECT_TRUE(fs::exists(run + "/eval-test/metrics.json"));
}

// run.threads 2 with run.ranks at auto: `layers train` starts two ranks of
// one thread that share each batch, so it makes the steps one process
// makes (same count, the same validation error), and records the
// experiment as given. A number of ranks that does not share the batch is
// one line; threads that do not share it leave one process.
TEST_F(CliLaunch, TrainStartsItsOwnRanksThatShareTheBatch) {
  const std::string two = dir.file("two"), one = dir.file("one");
  auto ranked =
      run_command(layers_cmd() + " train " + experiment + " --quiet --set run.threads=2 --set run.output=" + two);
  ASSERT_EQ(ranked.exit_code, 0) << ranked.output;
  EXPECT_EQ(count(ranked.output, "trained 1 epochs (4 steps)"), 1) << ranked.output;
  EXPECT_NE(ranked.output.find(" on 2 ranks, "), std::string::npos) << ranked.output;
  auto single = run_command(layers_cmd() + " train " + experiment +
                            " --quiet --set run.threads=2 --set run.ranks=1 --set run.output=" + one);
  ASSERT_EQ(single.exit_code, 0) << single.output;
  EXPECT_NE(single.output.find("trained 1 epochs (4 steps)"), std::string::npos) << single.output;
  EXPECT_EQ(single.output.find(" ranks, "), std::string::npos) << single.output;
  const auto val_error = [](const std::string& text) {
    const std::size_t at = text.find("val error ");
    return at == std::string::npos ? std::string("none") : text.substr(at, text.find(" mm", at) - at);
  };
  EXPECT_EQ(val_error(ranked.output), val_error(single.output)) << ranked.output << single.output;
  const std::string recorded = read_text_file(two + "/experiment.yaml");
  EXPECT_NE(recorded.find("batch_size: 2"), std::string::npos) << recorded;
  EXPECT_NE(recorded.find("threads: 2"), std::string::npos) << recorded;

  auto uneven = run_command(layers_cmd() + " train " + experiment +
                            " --quiet --set run.ranks=3 --set run.output=" + dir.file("three"));
  EXPECT_EQ(uneven.exit_code, 1) << uneven.output;
  EXPECT_NE(from_error(uneven.output)
                .find("run.ranks: expected a number of ranks that shares train.batch_size (2) evenly, got 3"),
            std::string::npos)
      << uneven.output;
  EXPECT_FALSE(fs::exists(dir.file("three")));
  auto odd = run_command(layers_cmd() + " train " + experiment +
                         " --quiet --set run.threads=3 --set run.output=" + dir.file("odd"));
  ASSERT_EQ(odd.exit_code, 0) << odd.output;
  EXPECT_EQ(odd.output.find(" ranks, "), std::string::npos) << odd.output;
  EXPECT_NE(odd.output.find("not shared evenly by 3 ranks"), std::string::npos) << odd.output;
}

TEST_F(CliLaunch, ExitCodesAreForwarded) {
  auto usage = run_command(layers_cmd() + " launch --nproc 2 -- no-such-verb");
  EXPECT_EQ(usage.exit_code, 2) << usage.output;
  const std::string bad = dir.write("bad.yaml", "include: exp.yaml\ntrain: {epochs: -1}\n");
  auto input = run_command(layers_cmd() + " launch --nproc 2 -- train " + bad);
  EXPECT_EQ(input.exit_code, 1) << input.output;
  // The first rank's line (the launcher may stop the other before it prints its own).
  EXPECT_GE(count(input.output, "bad.yaml:2: train.epochs: expected"), 1) << input.output;
  EXPECT_EQ(run_command(layers_cmd() + " launch --nproc 0 -- train " + experiment).exit_code, 2);
  EXPECT_EQ(run_command(layers_cmd() + " launch --nproc 2").exit_code, 2);
  EXPECT_EQ(run_command(layers_cmd() + " launch --nproc 2 -- launch --nproc 2 -- train x").exit_code, 2);
}

TEST_F(CliLaunch, BadDistributedVariablesAreOneLine) {
  auto bad = run_command(layers_cmd("RANK=5 WORLD_SIZE=2 MASTER_ADDR=127.0.0.1 MASTER_PORT=29999") + " train " +
                         experiment + " --quiet");
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_EQ(from_error(bad.output),
            "layers: error: environment: RANK: expected an integer in [0, 2) (WORLD_SIZE), got '5'\n");
  EXPECT_FALSE(fs::exists(run)) << "nothing written";
  auto port = run_command(layers_cmd("RANK=0 WORLD_SIZE=2 MASTER_ADDR=127.0.0.1 MASTER_PORT=http") + " eval " +
                          experiment + " --quiet");
  EXPECT_EQ(port.exit_code, 1) << port.output;
  EXPECT_EQ(from_error(port.output),
            "layers: error: environment: MASTER_PORT: expected a TCP port in [1, 65535], got 'http'\n");
}

TEST_F(CliLaunch, AMissingRankIsOneLineWithinTheTimeout) {
  auto alone = run_command(layers_cmd("RANK=0 WORLD_SIZE=2 MASTER_ADDR=127.0.0.1 MASTER_PORT=29998") + " train " +
                           experiment + " --quiet --set run.dist_timeout_s=2");
  EXPECT_EQ(alone.exit_code, 1) << alone.output;
  const std::string error = from_error(alone.output);
  EXPECT_EQ(error.rfind("layers: error: rank 0 of 2: rendezvous with 2 ranks at 127.0.0.1:29998 failed", 0), 0u)
      << alone.output;
  EXPECT_NE(error.find("did not answer within 2 s"), std::string::npos) << alone.output;
  EXPECT_EQ(std::count(error.begin(), error.end(), '\n'), 1) << alone.output;
}

}  // namespace
