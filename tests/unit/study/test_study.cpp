// The scheduling of `layers run` (layers/study/study.h) with actions that
// write the files the real steps write: what runs, what is current, what a
// deleted checkpoint, a changed override, a failure or an interrupted
// training reruns, dry runs, required studies and bad study files.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>

#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/study/study.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace fs = std::filesystem;
using namespace layers;
using study::StepStatus;

namespace {

class StudyTest : public testing::Test {
 protected:
  void SetUp() override {
    dir.write("gen.yaml", "name: fixture\n");
    dir.write("exp.yaml", "model: {name: anything, params: {}}\neval: {save_predictions: false}\n");
    study_file = write_study("study.yaml", "out", "a", "");
  }

  // A study with runs a and b (b's name and extra lines configurable).
  std::string write_study(const std::string& file, const std::string& output, const std::string& first,
                          const std::string& extra) {
    return dir.write(file, "output: " + dir.file(output) + "\ndataset: {config: gen.yaml, folder: " + dir.file("data") +
                               "}\nsteps: [train, eval, bench, report]\nexperiments:\n  - {name: " + first +
                               ", file: exp.yaml}\n  - {name: b, file: exp.yaml}\n" + extra);
  }

  static void touch(const fs::path& p, const std::string& text = "x") {
    fs::create_directories(p.parent_path());
    std::ofstream(p) << text;
  }

  study::StudyActions actions() {
    study::StudyActions a;
    a.dataset = [this](const study::StudyDataset& d) {
      calls["dataset"]++;
      if (fs::exists(fs::path(d.folder) / "dataset.yaml")) return false;
      for (const char* f : {"dataset.yaml", "splits.yaml", "stats.h5", "shard-00000.h5"}) touch(fs::path(d.folder) / f);
      return true;
    };
    a.train = [this](const study::StudyRun& run, bool resume) {
      calls["train " + run.name]++;
      if (resume) calls["resume " + run.name]++;
      if (fail_train == run.name) throw Error("training diverged");
      touch(fs::path(run.dir) / "checkpoint-last.pt");
      touch(fs::path(run.dir) / "checkpoint-best.pt");
    };
    a.eval = [this](const study::StudyRun& run, const std::string& split) {
      calls["eval " + run.name]++;
      touch(fs::path(run.dir) / ("eval-" + split) / "metrics.json", "{}");
      touch(fs::path(run.dir) / ("eval-" + split) / "sequences.csv");
    };
    a.bench = [this](const study::StudyRun& run, const train::BenchOptions& options) {
      calls["bench " + run.name]++;
      bench_split[run.name] = options.split;
      bench_checkpoint[run.name] = options.checkpoint;
      touch(fs::path(run.dir) / "bench.json", "{}");
    };
    a.report = [this](const study::StudyConfig&, const std::vector<std::string>& runs, const std::string& out) {
      calls["report"]++;
      report_runs = runs.size();
      touch(fs::path(out) / "report.md");
    };
    return a;
  }

  study::StudyResult run(const std::vector<std::string>& sets = {}, study::StudyOptions options = {}) {
    return study::run_study(study_file, sets, actions(), options);
  }

  // Status of one step ("a train", "report", ...) in a result.
  static StepStatus status(const study::StudyResult& r, const std::string& who) {
    for (const auto& o : r.steps)
      if ((o.run.empty() ? o.step : o.run + " " + o.step) == who) return o.status;
    ADD_FAILURE() << "no step " << who;
    return StepStatus::Blocked;
  }

  test::TempDir dir{"layers-study"};
  std::string study_file;
  std::map<std::string, int> calls;
  std::map<std::string, std::string> bench_split;       // per run: BenchOptions::split of its last bench
  std::map<std::string, std::string> bench_checkpoint;  // per run: BenchOptions::checkpoint of its last bench
  std::string fail_train;
  std::size_t report_runs = 0;
};

TEST_F(StudyTest, SecondRunReusesEverything) {
  const auto first = run();
  EXPECT_TRUE(first.ok());
  EXPECT_EQ(first.count(StepStatus::Ran), 8u);  // dataset, 2 x (train, eval-test, bench), report
  EXPECT_EQ(report_runs, 2u);
  EXPECT_EQ(first.report, dir.file("out") + "/report/report.md");
  EXPECT_TRUE(fs::exists(dir.file("out/a/experiment.yaml")));
  EXPECT_NE(read_text_file(dir.file("out/a/experiment.yaml")).find("output: " + dir.file("out") + "/a"),
            std::string::npos);

  const auto second = run();
  EXPECT_TRUE(second.ok());
  EXPECT_EQ(second.count(StepStatus::Ran), 0u);
  EXPECT_EQ(second.count(StepStatus::Current), 8u);
  EXPECT_EQ(calls["train a"], 1);
  EXPECT_EQ(calls["eval b"], 1);
  EXPECT_EQ(calls["report"], 1);
}

TEST_F(StudyTest, DeletedCheckpointRerunsOnlyWhatDependsOnIt) {
  run();
  fs::remove(dir.file("out/a/checkpoint-best.pt"));
  const auto r = run();
  EXPECT_EQ(status(r, "a train"), StepStatus::Ran);
  EXPECT_EQ(status(r, "a eval-test"), StepStatus::Ran);
  EXPECT_EQ(status(r, "a bench"), StepStatus::Ran);
  EXPECT_EQ(status(r, "report"), StepStatus::Ran);
  EXPECT_EQ(status(r, "b train"), StepStatus::Current);
  EXPECT_EQ(status(r, "b eval-test"), StepStatus::Current);
  EXPECT_EQ(status(r, "b bench"), StepStatus::Current);
  EXPECT_EQ(calls["resume a"], 0);  // a finished training is redone from the start
}

TEST_F(StudyTest, EvaluationSettingsRerunEvaluationNotTraining) {
  run();
  const auto r = run({"set=[eval.horizon=5]"});
  EXPECT_EQ(status(r, "a train"), StepStatus::Current);
  EXPECT_EQ(status(r, "a eval-test"), StepStatus::Ran);
  EXPECT_EQ(status(r, "b eval-test"), StepStatus::Ran);
  const auto t = run({"set=[eval.horizon=5, train.epochs=1]"});
  EXPECT_EQ(status(t, "a train"), StepStatus::Ran);
  EXPECT_EQ(status(t, "a eval-test"), StepStatus::Ran);
}

// How a run is spread over processes is not what it computes: run.ranks
// and run.dist_timeout_s leave every step current.
TEST_F(StudyTest, RanksAndTimeoutsLeaveTheStepsCurrent) {
  run();
  const auto r = run({"set=[run.ranks=1, run.dist_timeout_s=5]"});
  EXPECT_EQ(status(r, "a train"), StepStatus::Current);
  EXPECT_EQ(status(r, "a eval-test"), StepStatus::Current);
  EXPECT_EQ(status(r, "b train"), StepStatus::Current);
}

// A setting added after a study ran leaves its records current at the
// default (train.patience 0 is how every earlier run trained), and
// reruns the training when it is set.
TEST_F(StudyTest, ALaterSettingAtItsDefaultLeavesTheStepsCurrent) {
  run();
  const auto same = run({"set=[train.patience=0]"});
  EXPECT_EQ(status(same, "a train"), StepStatus::Current);
  EXPECT_EQ(status(same, "b eval-test"), StepStatus::Current);
  const auto set = run({"set=[train.patience=2]"});
  EXPECT_EQ(status(set, "a train"), StepStatus::Ran);
}

// The bench times a scene of the split the run is evaluated on: a study
// evaluated on validation never opens the test split, and changing the
// evaluated split benches again.
TEST_F(StudyTest, BenchTimesASceneOfTheEvaluatedSplit) {
  run();
  EXPECT_EQ(bench_split["a"], "test");
  const auto r = run({"eval.splits=[val]"});
  EXPECT_EQ(status(r, "a train"), StepStatus::Current);
  EXPECT_EQ(status(r, "a eval-val"), StepStatus::Ran);
  EXPECT_EQ(status(r, "a bench"), StepStatus::Ran);
  EXPECT_EQ(bench_split["a"], "val");
  EXPECT_EQ(bench_split["b"], "val");
}

TEST_F(StudyTest, CopiedStudyAndDatasetStayCurrent) {
  run();
  ASSERT_EQ(std::system(("cp -a " + dir.file("out") + " " + dir.file("out2") + " && cp -a " + dir.file("data") + " " +
                         dir.file("data2"))
                            .c_str()),
            0);
  const auto r = run({"output=" + dir.file("out2"), "dataset.folder=" + dir.file("data2")});
  EXPECT_EQ(r.count(StepStatus::Ran), 1u);  // the report: it names the run folders
  EXPECT_EQ(status(r, "report"), StepStatus::Ran);
  EXPECT_EQ(calls["train a"], 1);
  EXPECT_EQ(calls["dataset"], 2);  // asked, found complete
}

TEST_F(StudyTest, FailureBlocksOnlyItsRun) {
  fail_train = "a";
  const auto r = run();
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(status(r, "a train"), StepStatus::Failed);
  EXPECT_EQ(status(r, "a eval-test"), StepStatus::Blocked);
  EXPECT_EQ(status(r, "a bench"), StepStatus::Blocked);
  EXPECT_EQ(status(r, "b eval-test"), StepStatus::Ran);
  EXPECT_EQ(status(r, "report"), StepStatus::Ran);  // the report lists what is missing
  for (const auto& o : r.steps) {
    if (o.status == StepStatus::Failed) {
      EXPECT_NE(o.message.find("training diverged"), std::string::npos);
    }
  }
  fail_train.clear();
  const auto again = run();
  EXPECT_TRUE(again.ok());
  EXPECT_EQ(status(again, "a train"), StepStatus::Ran);
  EXPECT_EQ(calls["resume a"], 0);  // a failed training starts over
  EXPECT_EQ(status(again, "b train"), StepStatus::Current);
  EXPECT_EQ(status(again, "report"), StepStatus::Ran);
}

TEST_F(StudyTest, InterruptedTrainingResumes) {
  run();
  // What a killed `layers run` leaves: the record says started.
  const std::string steps = dir.file("out/a/steps.yaml");
  std::string text = read_text_file(steps);
  text.replace(text.find("state: done"), 11, "state: started");
  std::ofstream(steps) << text;
  const auto r = run();
  EXPECT_EQ(status(r, "a train"), StepStatus::Ran);
  EXPECT_EQ(calls["resume a"], 1);
}

TEST_F(StudyTest, DryRunRunsNothingAndMarksDependents) {
  run();
  fs::remove(dir.file("out/b/checkpoint-last.pt"));
  study::StudyOptions dry;
  dry.dry_run = true;
  const auto r = run({}, dry);
  EXPECT_EQ(status(r, "b train"), StepStatus::WouldRun);
  EXPECT_EQ(status(r, "b eval-test"), StepStatus::WouldRun);
  EXPECT_EQ(status(r, "report"), StepStatus::WouldRun);
  EXPECT_EQ(status(r, "a eval-test"), StepStatus::Current);
  EXPECT_EQ(calls["train b"], 1);
  EXPECT_FALSE(fs::exists(dir.file("out/b/checkpoint-last.pt")));
}

TEST_F(StudyTest, OnlyAndForce) {
  run();
  study::StudyOptions o;
  o.only = {"b"};
  o.force = true;
  const auto r = run({}, o);
  EXPECT_EQ(calls["train b"], 2);
  EXPECT_EQ(calls["train a"], 1);
  for (const auto& s : r.steps) EXPECT_NE(s.step, "report");
  o.only = {"c"};
  EXPECT_THROW(run({}, o), InputError);
}

// Lanes: each run's steps go to the lane action (here the same study run
// in-process with --only, one lane at a time under a lock, as a child
// `layers run --only` would); this process then finds them current and
// writes the report. A failed lane blocks its run only.
TEST_F(StudyTest, LanesRunEachRunElsewhereThenReport) {
  std::mutex lock;
  std::vector<std::string> lanes;
  std::string fail_lane;
  study::StudyActions a = actions();
  a.lane = [&](const study::StudyRun& run) {
    const std::lock_guard<std::mutex> hold(lock);
    lanes.push_back(run.name);
    if (run.name == fail_lane) return false;
    study::StudyOptions one;
    one.only = {run.name};
    return study::run_study(study_file, {}, actions(), one).ok();
  };
  study::StudyOptions o;
  o.lanes = 2;
  const auto r = study::run_study(study_file, {}, a, o);
  EXPECT_TRUE(r.ok());
  std::sort(lanes.begin(), lanes.end());
  EXPECT_EQ(lanes, (std::vector<std::string>{"a", "b"}));
  EXPECT_EQ(calls["train a"], 1);  // in its lane only
  EXPECT_EQ(calls["train b"], 1);
  EXPECT_EQ(status(r, "a train"), StepStatus::Current);
  EXPECT_EQ(status(r, "b bench"), StepStatus::Current);
  EXPECT_EQ(status(r, "report"), StepStatus::Ran);
  EXPECT_EQ(report_runs, 2u);

  // A lane that fails: its run is blocked, the other is current, and the
  // report is not blocked (current here: none of its inputs changed).
  fail_lane = "b";
  fs::remove(dir.file("out/b/checkpoint-best.pt"));
  const auto failed = study::run_study(study_file, {}, a, o);
  EXPECT_FALSE(failed.ok());
  EXPECT_EQ(status(failed, "b (all steps)"), StepStatus::Blocked);
  EXPECT_EQ(status(failed, "a train"), StepStatus::Current);
  EXPECT_EQ(status(failed, "report"), StepStatus::Current);

  // Dry runs start no lane; lanes below 1, or with --force, are refused.
  lanes.clear();
  o.dry_run = true;
  study::run_study(study_file, {}, a, o);
  EXPECT_TRUE(lanes.empty());
  o.dry_run = false;
  o.force = true;
  EXPECT_THROW(study::run_study(study_file, {}, a, o), UsageError);
  o.force = false;
  o.lanes = 0;
  EXPECT_THROW(study::run_study(study_file, {}, a, o), UsageError);
}

TEST_F(StudyTest, RequiredStudyRunsFirstAndLendsItsCheckpoint) {
  const std::string other =
      dir.write("stability.yaml", "requires: [study.yaml]\noutput: " + dir.file("stab") +
                                      "\ndataset: {config: gen.yaml, folder: " + dir.file("data") +
                                      "}\nsteps: [train, eval]\nset: [eval.horizon=0]\nexperiments:\n"
                                      "  - {name: a, file: exp.yaml, checkpoint: " +
                                      dir.file("out/a") + "}\n");
  const auto r = study::run_study(other, {}, actions(), {});
  EXPECT_TRUE(r.ok());
  EXPECT_EQ(calls["train a"], 1);  // in the required study only
  EXPECT_EQ(calls["eval a"], 2);
  EXPECT_TRUE(fs::exists(dir.file("stab/a/eval-test/metrics.json")));
  EXPECT_FALSE(fs::exists(dir.file("stab/a/checkpoint-best.pt")));
  // The lent checkpoint changes: only the evaluation that uses it reruns.
  fs::remove(dir.file("out/a/checkpoint-best.pt"));
  const auto again = study::run_study(other, {}, actions(), {});
  EXPECT_EQ(calls["train a"], 2);
  EXPECT_EQ(calls["eval a"], 4);
  EXPECT_EQ(calls["eval b"], 1);
  // A bench step times the lent weights, not the borrowing run's own.
  bench_checkpoint.clear();
  const std::string timed = dir.write("timed.yaml", "requires: [study.yaml]\noutput: " + dir.file("timed") +
                                                        "\ndataset: {config: gen.yaml, folder: " + dir.file("data") +
                                                        "}\nsteps: [eval, bench]\nexperiments:\n"
                                                        "  - {name: a, file: exp.yaml, checkpoint: " +
                                                        dir.file("out/a") + "}\n");
  ASSERT_TRUE(study::run_study(timed, {}, actions(), {}).ok());
  EXPECT_EQ(bench_checkpoint["a"], dir.file("out/a") + "/checkpoint-best.pt");
}

TEST_F(StudyTest, RequiredCycleAndMissingCheckpointAreReported) {
  dir.write("x.yaml",
            "requires: [y.yaml]\ndataset: {config: gen.yaml, folder: d}\nexperiments: [{name: a, file: exp.yaml}]\n");
  const std::string y = dir.write(
      "y.yaml",
      "requires: [x.yaml]\ndataset: {config: gen.yaml, folder: d}\nexperiments: [{name: a, file: exp.yaml}]\n");
  EXPECT_THROW(study::run_study(y, {}, actions(), {}), InputError);

  const std::string lone = dir.write("lone.yaml", "output: " + dir.file("lone") +
                                                      "\ndataset: {config: gen.yaml, folder: " + dir.file("data") +
                                                      "}\nsteps: [eval]\nexperiments:\n"
                                                      "  - {name: a, file: exp.yaml, checkpoint: " +
                                                      dir.file("nowhere") + "}\n");
  const auto r = study::run_study(lone, {}, actions(), {});
  EXPECT_FALSE(r.ok());
  EXPECT_EQ(status(r, "a eval-test"), StepStatus::Blocked);
  for (const auto& o : r.steps) {
    if (o.step == "eval-test") {
      EXPECT_NE(o.message.find("requires"), std::string::npos) << o.message;
    }
  }
}

TEST_F(StudyTest, SelectionOnTheTestSplitIsRefused) {
  // The best checkpoint is chosen on data.val_split: a study whose
  // experiment validates (or trains) on the test split is refused before
  // anything runs, naming the file and the key; dry runs too.
  for (const char* key : {"val_split", "train_split"}) {
    dir.write("peek.yaml", std::string("model: {name: anything, params: {}}\ndata: {") + key + ": test}\n");
    const std::string f = dir.write("peek_study.yaml", "output: " + dir.file("peek") +
                                                           "\ndataset: {config: gen.yaml, folder: " + dir.file("data") +
                                                           "}\nexperiments: [{name: a, file: peek.yaml}]\n");
    for (bool dry : {false, true}) {
      study::StudyOptions o;
      o.dry_run = dry;
      try {
        study::run_study(f, {}, actions(), o);
        ADD_FAILURE() << key << ": not refused";
      } catch (const InputError& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("peek.yaml"), std::string::npos) << m;
        EXPECT_NE(m.find(std::string("data.") + key), std::string::npos) << m;
      }
    }
    EXPECT_EQ(calls["train a"], 0);
  }
  // The same experiment with its own validation split runs.
  dir.write("peek.yaml", "model: {name: anything, params: {}}\ndata: {val_split: val}\n");
  EXPECT_TRUE(study::run_study(dir.file("peek_study.yaml"), {}, actions(), {}).ok());
}

// An experiment repeated over seeds is one run per seed, <name>/seed-<s>
// with run.seed = s (from the experiment's run.seed on): listed by a dry
// run, fingerprinted and skipped each on its own, picked by --only.
TEST_F(StudyTest, SeedsRepeatAnExperimentAsRunsOfTheirOwn) {
  study_file = dir.write("seeds.yaml", "output: " + dir.file("sd") +
                                           "\ndataset: {config: gen.yaml, folder: " + dir.file("data") +
                                           "}\nsteps: [train, eval, report]\nexperiments:\n"
                                           "  - {name: a, file: exp.yaml, seeds: 3, set: [run.seed=5]}\n"
                                           "  - {name: b, file: exp.yaml}\n");
  const std::vector<study::StudyRun> runs = study::resolve_runs(study::load_study(study_file));
  ASSERT_EQ(runs.size(), 4u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_EQ(runs[k].name, "a/seed-" + std::to_string(5 + k));
    EXPECT_EQ(runs[k].experiment, "a");
    EXPECT_EQ(runs[k].dir, dir.file("sd/a/seed-" + std::to_string(5 + k)));
    EXPECT_EQ(runs[k].config.run.seed, 5 + k);
    EXPECT_EQ(runs[k].config.run.output, runs[k].dir);
  }
  EXPECT_EQ(runs[3].name, "b");  // one seed: the plain run folder
  EXPECT_EQ(runs[3].dir, dir.file("sd/b"));

  // The dry run lists every repetition and writes nothing.
  study::StudyOptions dry;
  dry.dry_run = true;
  const auto listed = run({}, dry);
  for (const char* who : {"a/seed-5 train", "a/seed-6 train", "a/seed-7 train", "b train", "a/seed-6 eval-test"})
    EXPECT_EQ(status(listed, who), StepStatus::WouldRun) << who;
  EXPECT_FALSE(fs::exists(dir.file("sd/a")));

  const auto first = run();
  EXPECT_TRUE(first.ok());
  EXPECT_EQ(calls["train a/seed-6"], 1);
  EXPECT_EQ(report_runs, 4u);
  EXPECT_NE(read_text_file(dir.file("sd/a/seed-6/experiment.yaml")).find("seed: 6"), std::string::npos);
  // Each repetition is its own run: losing one seed's checkpoint reruns that seed only.
  fs::remove(dir.file("sd/a/seed-7/checkpoint-best.pt"));
  const auto again = run();
  EXPECT_EQ(status(again, "a/seed-7 train"), StepStatus::Ran);
  EXPECT_EQ(status(again, "a/seed-5 train"), StepStatus::Current);
  EXPECT_EQ(status(again, "a/seed-6 eval-test"), StepStatus::Current);

  // --only: an experiment is all its seeds, a run one of them.
  study::StudyOptions only;
  only.force = true;
  only.only = {"a/seed-5"};
  run({}, only);
  EXPECT_EQ(calls["train a/seed-5"], 2);
  EXPECT_EQ(calls["train a/seed-6"], 1);
  only.only = {"a"};
  run({}, only);
  EXPECT_EQ(calls["train a/seed-6"], 2);
  EXPECT_EQ(calls["train b"], 1);

  // The study's seeds repeat every experiment without its own.
  const auto both = study::resolve_runs(study::load_study(study_file, {"seeds=2"}));
  EXPECT_EQ(both.size(), 5u);
  EXPECT_EQ(both.back().name, "b/seed-1");
}

TEST_F(StudyTest, BadStudyFilesNameFileAndKey) {
  auto message = [&](const std::string& text) -> std::string {
    const std::string f = dir.write("bad.yaml", text);
    try {
      study::load_study(f);
    } catch (const InputError& e) {
      return e.what();
    }
    return "no error";
  };
  const std::string head = "dataset: {config: gen.yaml, folder: d}\n";
  EXPECT_NE(message(head + "steps: [train, plot]\nexperiments: [{name: a, file: exp.yaml}]\n").find("steps[1]"),
            std::string::npos);
  EXPECT_NE(message(head + "experiments: [{name: a, file: exp.yaml}, {name: a, file: exp.yaml}]\n")
                .find("experiments[1].name"),
            std::string::npos);
  EXPECT_NE(message(head + "experiments: [{name: a/b, file: exp.yaml}]\n").find("experiments[0].name"),
            std::string::npos);
  EXPECT_NE(message(head + "experiments: [{name: a, file: missing.yaml}]\n").find("missing.yaml"), std::string::npos);
  EXPECT_NE(message("dataset: {config: nope.yaml, folder: d}\nexperiments: [{name: a, file: exp.yaml}]\n")
                .find("dataset.config"),
            std::string::npos);
  EXPECT_NE(
      message("dataset: {folder: d, set: [frames=3]}\nexperiments: [{name: a, file: exp.yaml}]\n").find("dataset.set"),
      std::string::npos);
  EXPECT_NE(message(head + "experiments: [{name: a, file: exp.yaml}]\ncolour: red\n").find("colour"),
            std::string::npos);
  EXPECT_NE(message(head + "experiments: []\n").find("experiments"), std::string::npos);
  EXPECT_NE(message(head + "experiments: [{name: a, file: exp.yaml, seeds: -1}]\n").find("seeds"), std::string::npos);
}

// Without dataset.config the folder is a finished dataset: it is handed to
// the dataset action with no config (which must not generate) and the
// runs go on from it.
TEST_F(StudyTest, FinishedDatasetWithoutConfig) {
  for (const char* f : {"dataset.yaml", "splits.yaml", "stats.h5", "shard-00000.h5"}) touch(dir.file("fixed/") + f);
  const std::string y =
      dir.write("fixed.yaml", "output: " + dir.file("out") + "\ndataset: {folder: " + dir.file("fixed") +
                                  "}\nsteps: [train, eval]\nexperiments: [{name: a, file: exp.yaml}]\n");
  const study::StudyConfig loaded = study::load_study(y);
  EXPECT_TRUE(loaded.dataset.config.empty());
  study_file = y;
  study::StudyActions a = actions();
  a.dataset = [this](const study::StudyDataset& d) {
    calls["dataset"]++;
    EXPECT_TRUE(d.config.empty());
    return false;
  };
  const study::StudyResult r = study::run_study(study_file, {}, a, {});
  EXPECT_EQ(status(r, "dataset"), StepStatus::Current);
  EXPECT_EQ(status(r, "a train"), StepStatus::Ran);
  EXPECT_EQ(status(r, "a eval-test"), StepStatus::Ran);
}

TEST(StudyFingerprint, StampsAndHashes) {
  test::TempDir dir;
  EXPECT_EQ(study::fingerprint_text("abc"), study::fingerprint_text("abc"));
  EXPECT_NE(study::fingerprint_text("abc"), study::fingerprint_text("abd"));
  EXPECT_EQ(study::fingerprint_text("abc").size(), 16u);
  EXPECT_EQ(study::file_stamp(dir.file("none")), "missing");
  const std::string f = dir.write("f", "12345");
  EXPECT_EQ(study::file_stamp(f).substr(0, 2), "5:");
  const std::string before = study::dataset_fingerprint(dir.path());
  dir.write("shard-00000.h5", "x");
  EXPECT_NE(study::dataset_fingerprint(dir.path()), before);
  EXPECT_EQ(study::dataset_fingerprint(dir.file("nope")), "missing");
}

}  // namespace

// The paper's rows of Table 4 as the paper defines them (docs/reproduction.md):
// DeePSD+ with the body and the layer collision terms, LayersNet+ with the
// body term at the paper's weight 1, LayersNet's radii as appendix A.3 gives
// them (body 0.4, between layers 0.6 at its 10x scale), our variant keeping
// the radii it was chosen with.
TEST(PaperRows, Table4DefinesThePaperRowsAsThePaperDoes) {
  const std::string file = layers::test::source_dir() + "/configs/studies/table4_small.yaml";
  std::map<std::string, train::ExperimentConfig> by_name;
  for (const study::StudyRun& run : study::resolve_runs(study::load_study(file))) by_name[run.name] = run.config;
  const auto loss = [&](const std::string& name) { return by_name.at(name + "/seed-0").loss; };
  EXPECT_EQ(loss("deepsd").body_collision, 0.0);
  EXPECT_EQ(loss("deepsd").layer_collision, 0.0);
  EXPECT_EQ(loss("deepsd+").body_collision, 1.0);
  EXPECT_EQ(loss("deepsd+").layer_collision, 1.0);
  EXPECT_EQ(loss("layersnet").body_collision, 0.0);
  EXPECT_EQ(loss("layersnet+").body_collision, 1.0);
  EXPECT_EQ(loss("layersnet+").layer_collision, 0.0);
  const auto radius = [&](const std::string& name, const char* key) {
    const cfg::Node* params = by_name.at(name + "/seed-0").model.find("params");
    const cfg::Node* value = params ? params->find(key) : nullptr;
    return value ? std::stod(value->scalar) : -1.0;
  };
  EXPECT_EQ(radius("layersnet", "body_radius"), 0.04);
  EXPECT_EQ(radius("layersnet", "world_radius"), 0.06);
  EXPECT_EQ(radius("layersnet+", "body_radius"), 0.04);
  EXPECT_EQ(radius("layersnet-body-gate", "body_radius"), 0.06);
  EXPECT_EQ(radius("layersnet-body-gate", "world_radius"), 0.04);
}
