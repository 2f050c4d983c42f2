// `layers train` never loses a run: a folder that holds one is refused
// without --resume or --force, --force moves it aside (never deletes it),
// and a command that fails (unknown model) leaves the folder as it was;
// neither train nor eval lets a choice read the test split; `layers bench`
// says which split its scene is from.
// Trains the test plugin's one-parameter model on the regression fixture.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <nlohmann/json.hpp>

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

  // A resume from a damaged checkpoint fails before experiment.yaml is
  // written: the run's resolved experiment stays as it was.
  {
    std::string damaged = checkpoint;
    for (std::size_t i = damaged.size() / 2; i < damaged.size() / 2 + 64; ++i) damaged[i] ^= 0x5a;
    std::ofstream(run + "/checkpoint-last.pt", std::ios::binary) << damaged;
    auto broken = train(experiment, "--set train.lr=0.5 --resume");
    EXPECT_EQ(broken.exit_code, 1) << broken.output;
    EXPECT_NE(broken.output.find("checkpoint-last.pt: checksum"), std::string::npos) << broken.output;
    EXPECT_EQ(read_bytes(run + "/experiment.yaml"), resolved);
    std::ofstream(run + "/checkpoint-last.pt", std::ios::binary) << checkpoint;
  }

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

// The selection policy by hand: training or choosing the checkpoint on the
// test split is refused with one line before anything is written; the run
// folder and metrics.json record which split chose the checkpoint and
// which it is evaluated on; a checkpoint chosen on what the evaluation
// calls its test split is refused; one evaluated on the split that chose
// it is marked.
TEST(CliTrain, SelectionNeverReadsTheTestSplitAndIsRecorded) {
  test::TempDir dir("layers-cli-selection");
  const std::string data = regression::write_fixture(dir.path());
  const std::string run = dir.file("run");
  const std::string experiment =
      dir.write("exp.yaml", "model: {name: test_constant_velocity, params: {damping: 0.6}}\ndata: {dataset: " + data +
                                "}\ntrain: {epochs: 2, batch_size: 2, windows_per_epoch: 2, val_horizon: 2, "
                                "val_sequences: 1}\neval: {horizon: 3, save_predictions: false}\nrun: {output: " +
                                run + ", threads: 1, seed: 0}\n");
  for (const char* key : {"val_split", "train_split"}) {
    auto peek = train(experiment, std::string("--set data.") + key + "=test");
    EXPECT_EQ(peek.exit_code, 1) << peek.output;
    EXPECT_EQ(peek.output, "layers: error: " + experiment + ": data." + key +
                               ": expected a split other than data.test_split 'test' (training and the choice of "
                               "the best checkpoint never read the test split), got 'test'\n");
    EXPECT_FALSE(fs::exists(run));
  }

  auto trained = train(experiment);
  ASSERT_EQ(trained.exit_code, 0) << trained.output;
  const nlohmann::json selection = nlohmann::json::parse(read_bytes(run + "/selection.json"));
  EXPECT_EQ(selection["chosen_on"], "val");
  EXPECT_EQ(selection["epochs"], 2);
  EXPECT_GE(selection["chosen_epoch"].get<int>(), 1);

  const std::string eval =
      "LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin() + " eval " + experiment + " --quiet ";
  auto tested = run_command(eval);
  ASSERT_EQ(tested.exit_code, 0) << tested.output;
  EXPECT_NE(tested.output.find("checkpoint: best, chosen on val, evaluated on test\n"), std::string::npos)
      << tested.output;
  const nlohmann::json metrics = nlohmann::json::parse(read_bytes(run + "/eval-test/metrics.json"));
  EXPECT_EQ(metrics["selection"]["checkpoint"], "best");
  EXPECT_EQ(metrics["selection"]["chosen_on"], "val");
  EXPECT_EQ(metrics["selection"]["evaluated_on"], "test");
  EXPECT_EQ(metrics["selection"]["chosen_epoch"], selection["chosen_epoch"]);

  // The last checkpoint was chosen by nothing.
  auto last = run_command(eval + "--checkpoint last --out " + dir.file("last"));
  ASSERT_EQ(last.exit_code, 0) << last.output;
  EXPECT_EQ(nlohmann::json::parse(read_bytes(dir.file("last/metrics.json")))["selection"]["chosen_on"], "none");

  // Evaluated on the split that chose it: runs, marked.
  auto same = run_command(eval + "--split val");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("evaluated on val (the same split"), std::string::npos) << same.output;

  // By hand, eval refuses the same configs train does.
  auto peek = run_command(eval + "--set data.val_split=test");
  EXPECT_EQ(peek.exit_code, 1) << peek.output;
  EXPECT_NE(peek.output.find(experiment + ": data.val_split: expected a split other than data.test_split"),
            std::string::npos)
      << peek.output;
  // A checkpoint chosen on the split this evaluation calls its test split.
  auto chosen = run_command(eval + "--set data.test_split=val --set data.val_split=other --split val");
  EXPECT_EQ(chosen.exit_code, 1) << chosen.output;
  EXPECT_NE(chosen.output.find(run + "/checkpoint-best.pt: selection.chosen_on: expected a checkpoint chosen on a "
                                     "split other than data.test_split 'val', got one chosen on 'val'"),
            std::string::npos)
      << chosen.output;

  // `layers bench` times a scene of --split, else of the test split, and says which.
  const std::string bench = "LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin() + " bench " +
                            experiment + " --levels 0 --min-time 0.01 --no-far-body --no-train --out ";
  for (const char* split : {"", "val"}) {
    const std::string out = dir.file(std::string("bench-") + split + ".json");
    auto timed = run_command(bench + out + (*split ? std::string(" --split ") + split : std::string()));
    ASSERT_EQ(timed.exit_code, 0) << timed.output;
    EXPECT_EQ(nlohmann::json::parse(read_bytes(out))["split"], *split ? split : "test");
    // The weights timed are the run's best checkpoint, and bench.json says so.
    EXPECT_EQ(nlohmann::json::parse(read_bytes(out))["checkpoint"], run + "/checkpoint-best.pt");
  }
  // --profile: where an inference and a training step spend their time,
  // by phase (every millisecond of the step in one phase or outside the
  // profiled ranges) and operator, beside the machine's matrix-product peak.
  {
    const std::string out = dir.file("bench-profile.json");
    const std::string profiled = "LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin() + " bench " +
                                 experiment + " --levels 0 --min-time 0.01 --no-far-body --profile --profile-steps 2 " +
                                 "--out " + out;
    auto timed = run_command(profiled);
    ASSERT_EQ(timed.exit_code, 0) << timed.output;
    EXPECT_NE(timed.output.find("matrix-product peak:"), std::string::npos) << timed.output;
    const nlohmann::json doc = nlohmann::json::parse(read_bytes(out));
    EXPECT_GT(doc["matmul_peak_gflops"].get<double>(), 0.0);
    for (const char* kind : {"infer", "train"}) {
      const nlohmann::json& p = doc["rows"][0]["profile"][kind];
      ASSERT_TRUE(p.is_object()) << kind << ": " << doc.dump(1);
      EXPECT_EQ(p["steps"], 2);
      EXPECT_GT(p["ops"].get<double>(), 0.0) << kind;
      double phases = 0;
      for (const auto& phase : p["phases"]) phases += phase["ms"].get<double>();
      EXPECT_NEAR(phases, p["ms"].get<double>(), 1e-6 * p["ms"].get<double>()) << kind;
      EXPECT_FALSE(p["top_ops"].empty()) << kind;
    }
    bool backward = false;
    for (const auto& phase : doc["rows"][0]["profile"]["train"]["phases"]) backward |= phase["phase"] == "backward";
    EXPECT_TRUE(backward) << "a training step's backward pass is a phase of its own";
  }
  // A checkpoint file that is not there is an error, not the initial weights.
  auto missing = run_command(bench + dir.file("bench-missing.json") + " --checkpoint " + dir.file("none.pt"));
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find(dir.file("none.pt") + ": checkpoint: expected an existing file, got no such file"),
            std::string::npos)
      << missing.output;
}

// The epoch is chosen without reading the test split, by the real trainer:
// the fixture and a copy whose test sequences' garments stop after frame 1
// (a valid dataset, hashed as written) give the same chosen epoch, the same
// checkpoint bytes and the same selection.json. The control shows the
// change would be seen if read: with validation pointed at the test split,
// the two datasets choose different epochs, and the record says which
// split was read.
TEST(CliTrain, ChoosingTheEpochNeverReadsTheTestSplit) {
  test::TempDir dir("layers-cli-selection");
  const std::string original = regression::write_fixture(dir.path());
  const std::string altered = regression::write_fixture(
      dir.path(),
      [](data::SequenceData& seq) {
        for (data::GarmentData& g : seq.garments) {
          const std::size_t n = g.rest.size();
          for (std::int64_t t = 2; t < seq.n_frames; ++t)
            std::copy(g.positions.begin() + static_cast<std::ptrdiff_t>(n),
                      g.positions.begin() + static_cast<std::ptrdiff_t>(2 * n),
                      g.positions.begin() + static_cast<std::ptrdiff_t>(t * n));
        }
      },
      "altered");
  const auto run = [&](const std::string& data, const std::string& name, const std::string& extra) {
    const std::string experiment =
        dir.write(name + ".yaml",
                  "model: {name: test_constant_velocity, params: {damping: 0.6}}\n"
                  "data: {dataset: " +
                      data +
                      "}\n"
                      "train: {epochs: 5, batch_size: 2, windows_per_epoch: 8, lr: 0.05, val_horizon: 8}\n"
                      "run: {output: " +
                      dir.file(name) + ", threads: 1, seed: 0}\n");
    auto r = train(experiment, extra);
    EXPECT_EQ(r.exit_code, 0) << r.output;
    return nlohmann::json::parse(read_bytes(dir.file(name + "/selection.json")));
  };
  const nlohmann::json a = run(original, "original", "");
  const nlohmann::json b = run(altered, "altered-run", "");
  EXPECT_EQ(a["chosen_on"], "val");
  EXPECT_EQ(a["windows_by_epoch"], nlohmann::json::parse("[8, 8, 8, 8, 8]")) << "the learning curves' x axis";
  EXPECT_EQ(a, b);
  for (const char* file : {"checkpoint-best.pt", "checkpoint-last.pt"})
    EXPECT_TRUE(read_bytes(dir.file(std::string("original/") + file)) ==
                read_bytes(dir.file(std::string("altered-run/") + file)))
        << file << " differs";

  const std::string control = "--set data.val_split=test --set data.test_split=val";
  const nlohmann::json c = run(original, "control-original", control);
  const nlohmann::json d = run(altered, "control-altered", control);
  EXPECT_EQ(c["chosen_on"], "test") << "the record names the split the validation read";
  EXPECT_NE(c["val_error_mm_by_epoch"], d["val_error_mm_by_epoch"]);
  EXPECT_NE(c["chosen_epoch"], d["chosen_epoch"]) << c.dump() << "\n" << d.dump();
}
