// `layers train` never loses a run: a folder that holds one is refused
// without --resume or --force, --force moves it aside (never deletes it),
// and a command that fails (unknown model) leaves the folder as it was.
// Trains the test plugin's one-parameter model on the regression fixture.
#include <gtest/gtest.h>

#include <filesystem>

#include "file_bytes.h"
#include "run_command.h"
#include "synthetic_fixture.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

using test::read_bytes;

test::CommandResult train(const std::string& experiment, const std::string& extra = "") {
  return run_command("LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin() + " train " + experiment +
                     " --quiet " + extra);
}

}  // namespace

TEST(CliTrain, ExistingRunIsNeverOverwrittenOrLost) {
  test::TempDir dir("layers-cli-train");
  const std::string data = regression::write_fixture(dir.path());
  const std::string run = dir.file("run");
  const std::string experiment =
      dir.write("exp.yaml",
                "model: {name: test_constant_velocity, params: {damping: 0.6}}\n"
                "data: {dataset: " +
                    data +
                    "}\n"
                    "train: {epochs: 1, batch_size: 2, windows_per_epoch: 4, val_horizon: 2, val_sequences: 1}\n"
                    "run: {output: " +
                    run + ", threads: 1, seed: 0}\n");
  auto first = train(experiment);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const std::string checkpoint = read_bytes(run + "/checkpoint-last.pt");
  const std::string resolved = read_bytes(run + "/experiment.yaml");
  ASSERT_FALSE(checkpoint.empty());

  // Again without --resume: refused with one line, nothing touched.
  auto again = train(experiment, "--set train.lr=0.5");
  EXPECT_EQ(again.exit_code, 1) << again.output;
  EXPECT_NE(
      again.output.find(run + ": run.output: expected a new or empty run folder (--resume continues the run "
                              "there, --force moves it aside), got a folder holding a run (checkpoint-best.pt, ...)"),
      std::string::npos)
      << again.output;
  EXPECT_EQ(read_bytes(run + "/checkpoint-last.pt"), checkpoint);
  EXPECT_EQ(read_bytes(run + "/experiment.yaml"), resolved);

  // A failing train (unknown model) does not rewrite experiment.yaml.
  auto unknown = train(experiment, "--set model.name=no_such_model --resume");
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_NE(unknown.output.find("unknown model 'no_such_model'"), std::string::npos) << unknown.output;
  EXPECT_EQ(read_bytes(run + "/experiment.yaml"), resolved);

  // --resume and --force together are a usage error.
  EXPECT_EQ(train(experiment, "--resume --force").exit_code, 2);

  // --force starts afresh and keeps the old run beside it, byte for byte.
  auto forced = train(experiment, "--force");
  ASSERT_EQ(forced.exit_code, 0) << forced.output;
  std::string aside;
  for (const auto& e : fs::directory_iterator(dir.path()))
    if (e.path().filename().string().rfind("run.replaced-", 0) == 0) aside = e.path().string();
  ASSERT_FALSE(aside.empty()) << forced.output;
  EXPECT_NE(forced.output.find("moved the old run " + run + " aside to " + aside), std::string::npos) << forced.output;
  EXPECT_EQ(read_bytes(aside + "/checkpoint-last.pt"), checkpoint);
  EXPECT_EQ(read_bytes(aside + "/experiment.yaml"), resolved);
  EXPECT_TRUE(fs::exists(run + "/checkpoint-last.pt"));
}

// Flag values and config keys are checked before anything runs.
TEST(CliTrain, BadHorizonAndMissingDatasetAreNamed) {
  test::TempDir dir("layers-cli-eval");
  const std::string experiment =
      dir.write("exp.yaml", "model: {name: test_constant_velocity}\ndata: {dataset: " + dir.file("nothing") +
                                "}\nrun: {output: " + dir.file("run") + "}\n");
  auto horizon = run_command("LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin() + " eval " +
                             experiment + " --horizon -1000000");
  EXPECT_EQ(horizon.exit_code, 2) << horizon.output;
  EXPECT_NE(horizon.output.find("--horizon"), std::string::npos) << horizon.output;
  auto missing = train(experiment);
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_FALSE(fs::exists(dir.file("run"))) << "a failing train made its run folder";
  EXPECT_NE(missing.output.find(experiment +
                                ": data.dataset: expected a dataset folder (made by `layers generate`) "
                                "or shard file, got '" +
                                dir.file("nothing") + "' (no such folder or file)"),
            std::string::npos)
      << missing.output;
}
