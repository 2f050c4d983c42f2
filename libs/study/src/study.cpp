// The steps of a study -- dataset, then train, eval-<split> and bench of
// each run, then the report -- as data for the step loop, and the order of
// required studies (see study.h).
#include "layers/study/study.h"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <mutex>
#include <set>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/parallel.h"
#include "layers/core/progress.h"
#include "layers/core/text_file.h"
#include "layers/data/run_layout.h"
#include "lists.h"

namespace fs = std::filesystem;
namespace run_layout = layers::data::run_layout;

namespace layers::study {
namespace {

const char* const kDataset = "dataset";  // the dataset step's name

// Writes <dir>/experiment.yaml when it differs (reports read it).
void save_experiment(const StudyRun& run) {
  const fs::path file = fs::path(run.dir) / run_layout::kExperiment;
  if (fs::exists(file) && read_text_file(file.string()) == run.config_yaml) return;
  write_text_atomic(file.string(), run.config_yaml);
}

// The experiment as fingerprinted: without run.output and data.dataset
// (locations: the run folder holds the records, the dataset's files are
// fingerprinted themselves, so a study folder copied with its dataset
// stays current), without run.dist_timeout_s and run.ranks (how long
// ranks wait and how many processes share each batch, not what they
// compute; a study trains in its own process) and data.allow_unhashed (whether a dataset is
// verified, not what is computed from it) and, for training, without the eval section.
// A setting added after studies were run is left out at its default, so
// their records stay current: train.patience 0 (train every epoch).
std::string fingerprinted_text(const StudyRun& run, bool training) {
  cfg::Node tree = cfg::to_node(run.config);
  if (cfg::Node* r = tree.find("run")) r->erase("output"), r->erase("dist_timeout_s"), r->erase("ranks");
  if (cfg::Node* t = tree.find("train"); t != nullptr && run.config.train.patience == 0) t->erase("patience");
  if (cfg::Node* d = tree.find("data")) d->erase("dataset"), d->erase("allow_unhashed");
  if (training) tree.erase("eval");
  return cfg::to_yaml(tree);
}

Step dataset_step(const StudyDataset& dataset, const StudyActions& actions) {
  Step s;
  s.name = kDataset;
  s.would_run = [&dataset](std::string& message) {
    const fs::path folder(dataset.folder);
    const bool present = fs::exists(folder / "dataset.yaml") && fs::exists(folder / "splits.yaml");
    message = dataset.folder + (present ? " present" : " missing or incomplete");
    return !present;
  };
  s.work = [&dataset, &actions](StepWork& w) {
    w.current = !actions.dataset(dataset);
    w.message = dataset.folder;
  };
  return s;
}

// train, eval-<split> and bench of one run.
std::vector<Step> run_steps(const StudyConfig& study, const StudyRun& run, const std::string& dataset_fp,
                            const StudyActions& actions) {
  std::vector<Step> steps;
  std::vector<std::string> after{kDataset};
  if (contains(run.steps, "train")) {
    Step s;
    s.run = run.name, s.name = "train", s.after = after, s.folder = run.dir;
    const std::string inputs =
        Fingerprint().add("experiment", fingerprinted_text(run, true)).add("dataset", dataset_fp).str();
    s.inputs = [inputs] { return inputs; };
    s.outputs = {run_layout::checkpoint("last"), run_layout::checkpoint("best")};
    s.work = [&run, &actions](StepWork& w) {
      const bool resume = w.previous && w.previous->state == "started" && w.previous->inputs == w.inputs &&
                          fs::exists(fs::path(run.dir) / run_layout::checkpoint("last"));
      actions.train(run, resume);
    };
    after.push_back(s.id());
    steps.push_back(std::move(s));
  }
  // eval and bench read the checkpoint: fingerprinted when their turn comes.
  auto uses_checkpoint = [&](const std::string& name, const std::string& what) {
    Step s;
    s.run = run.name, s.name = name, s.after = after, s.folder = run.dir;
    s.inputs = [&run, dataset_fp, what] {
      return Fingerprint()
          .add("experiment", fingerprinted_text(run, false))
          .add("dataset", dataset_fp)
          .add("checkpoint", run.external_checkpoint ? run.checkpoint : fs::path(run.checkpoint).filename().string())
          .add("checkpoint_stamp", file_stamp(run.checkpoint))
          .add("step", what)
          .str();
    };
    s.blocked = [&run]() -> std::string {
      if (fs::exists(run.checkpoint)) return "";
      return "no checkpoint " + run.checkpoint +
             (run.external_checkpoint ? " (run the study that trains it first; see `requires:`)" : "");
    };
    return s;
  };
  if (contains(run.steps, "eval")) {
    for (const std::string& split : run.eval_splits) {
      const std::string name = run_layout::eval_folder(split);
      Step s = uses_checkpoint(name, name);
      s.outputs = {name + "/" + run_layout::kMetrics, name + "/" + run_layout::kSequences};
      if (run.config.eval.save_predictions) s.outputs.push_back(name + "/" + run_layout::kPredictions);
      s.work = [&run, &actions, split](StepWork&) { actions.eval(run, split); };
      steps.push_back(std::move(s));
    }
  }
  if (contains(run.steps, "bench")) {
    // Timed on a scene of the split the run is evaluated on (its first),
    // so that a study evaluated on validation never opens the test split.
    train::BenchOptions b = study.bench;
    b.split = run.eval_splits.front();
    b.checkpoint = run.checkpoint;  // what the evaluation reads, a lent one included
    const std::string opts = std::to_string(b.levels) + "/" + std::to_string(b.min_time) + "/" +
                             std::to_string(b.train) + "/" + std::to_string(b.far_body) + " on " + b.split;
    Step s = uses_checkpoint("bench", "bench " + opts);
    s.outputs = {run_layout::kBench};
    s.work = [&run, &actions, b](StepWork&) { actions.bench(run, b); };
    steps.push_back(std::move(s));
  }
  return steps;
}

// The report's inputs: every file of the runs it reads.
std::string report_inputs(const StudyConfig& study, const std::vector<StudyRun>& runs, const std::string& dataset_fp) {
  Fingerprint f;
  const StudyReport& r = study.report;
  f.add("options",
        r.title + "|" + r.split + "|" + std::to_string(r.charts) + "|" + std::to_string(r.frames) + "|" + r.sequence);
  f.add("dataset", dataset_fp);
  for (const StudyRun& run : runs) {
    const fs::path dir(run.dir);
    f.add("run", run.dir);
    f.add(run_layout::kExperiment, file_stamp((dir / run_layout::kExperiment).string()));
    f.add(run_layout::kBench, file_stamp((dir / run_layout::kBench).string()));
    for (const std::string& split : run.eval_splits)
      for (const char* file : {run_layout::kMetrics, run_layout::kPredictions}) {
        const std::string name = run_layout::eval_folder(split) + "/" + file;
        f.add(name, file_stamp((dir / name).string()));
      }
  }
  return f.str();
}

Step report_step(const StudyConfig& study, const std::vector<StudyRun>& runs, const std::vector<std::string>& after,
                 const std::string& dataset_fp, const StudyActions& actions) {
  Step s;
  s.name = "report", s.after = after, s.after_failures = true, s.folder = study.output;
  s.inputs = [&study, &runs, dataset_fp] { return report_inputs(study, runs, dataset_fp); };
  s.outputs = {std::string(run_layout::kReportFolder) + "/" + run_layout::kReport};
  s.work = [&study, &runs, &actions](StepWork&) {
    std::vector<std::string> dirs;
    for (const StudyRun& r : runs) dirs.push_back(r.dir);
    actions.report(study, dirs, (fs::path(study.output) / run_layout::kReportFolder).string());
  };
  return s;
}

// Hands every run to actions.lane, `lanes` at a time; returns the names of
// the runs whose lane failed.
std::set<std::string> run_lanes(const std::string& study, const std::vector<StudyRun>& runs, int lanes,
                                const StudyActions& actions) {
  std::mutex mutex;
  std::set<std::string> failed;
  const auto say = [&](const std::string& line) {
    const std::lock_guard<std::mutex> lock(mutex);
    std::printf("[%s] %s\n", study.c_str(), line.c_str());
    std::fflush(stdout);
  };
  // A lane's failure is recorded, never thrown: every run gets its lane.
  parallel_indices(runs.size(), lanes, [&](std::size_t i) {
    const StudyRun& run = runs[i];
    say(run.name + ": lane started");
    const Timer timer;
    bool ok = false;
    try {
      ok = actions.lane(run);
    } catch (const std::exception& e) {
      say(run.name + ": lane could not start: " + e.what());
    }
    say(run.name + (ok ? ": lane done in " : ": lane FAILED after ") + Progress::format_duration(timer.seconds()));
    if (!ok) {
      const std::lock_guard<std::mutex> lock(mutex);
      failed.insert(run.name);
    }
  });
  return failed;
}

// Studies in the order `requires` asks, each once.
class StudyOrder {
 public:
  StudyOrder(const StudyActions& actions, const StudyOptions& options, StudyResult& result)
      : actions_(actions), options_(options), result_(result) {}

  void run_file(const std::string& path, const std::vector<std::string>& sets, bool top) {
    const std::string key = fs::weakly_canonical(path).string();
    if (running_.count(key)) throw InputError(path, "requires", "no cycle of required studies", "a cycle");
    if (finished_.count(key)) return;
    running_.insert(key);
    const StudyConfig study = load_study(path, sets);
    for (const std::string& req : study.requires_) run_file(req, {}, false);
    run(study, top);
    running_.erase(key);
    finished_.insert(key);
  }

 private:
  void run(const StudyConfig& study, bool top) {
    std::vector<StudyRun> runs = resolve_runs(study);
    std::printf("[%s] study %s: %zu experiments", study.name.c_str(), study.source.c_str(), study.experiments.size());
    if (runs.size() != study.experiments.size()) std::printf(" (%zu runs over seeds)", runs.size());
    std::printf(", steps %s, output %s\n", join(study.steps).c_str(), study.output.c_str());
    std::fflush(stdout);
    const bool only = top && !options_.only.empty();
    if (only) {
      // --only names an experiment (all its seeds) or one run (<name>/seed-<s>).
      auto picked = [&](const StudyRun& r) {
        return contains(options_.only, r.name) || contains(options_.only, r.experiment);
      };
      std::vector<std::string> names;
      for (const StudyRun& r : runs) {
        if (!contains(names, r.experiment)) names.push_back(r.experiment);
        if (r.repeated) names.push_back(r.name);
      }
      for (const std::string& o : options_.only)
        if (!contains(names, o)) throw InputError(study.source, "--only " + o, "one of " + join(names), "'" + o + "'");
      runs.erase(std::remove_if(runs.begin(), runs.end(), [&](const StudyRun& r) { return !picked(r); }), runs.end());
    }
    const bool report = contains(study.steps, "report") && !only;

    Runner runner(study.name, {options_.force && top, options_.dry_run}, result_.steps);
    runner.run({dataset_step(study.dataset, actions_)});
    if (runner.status(kDataset) == StepStatus::Failed) {
      for (const StudyRun& r : runs) runner.block(r.name, "(all steps)", "no dataset");
      if (report) runner.block("", "report", "no dataset");
      return;
    }
    const std::string dataset_fp = dataset_fingerprint(study.dataset.folder);
    if (!options_.dry_run)
      for (const StudyRun& r : runs) {
        fs::create_directories(r.dir);
        save_experiment(r);
      }
    // Lanes run each run's steps elsewhere; the loop below then finds them
    // current, or blocks the runs whose lane failed.
    std::set<std::string> lane_failed;
    if (top && options_.lanes > 1 && !options_.dry_run && runs.size() > 1) {
      std::printf("[%s] %zu runs in %d lanes (logs: <run>/lane.log)\n", study.name.c_str(), runs.size(),
                  options_.lanes);
      std::fflush(stdout);
      lane_failed = run_lanes(study.name, runs, options_.lanes, actions_);
    }
    std::vector<Step> steps;
    for (const StudyRun& r : runs) {
      if (lane_failed.count(r.name)) {
        runner.block(r.name, "(all steps)", "its lane failed (" + (fs::path(r.dir) / "lane.log").string() + ")");
        continue;
      }
      for (Step& s : run_steps(study, r, dataset_fp, actions_)) steps.push_back(std::move(s));
    }
    if (report) {
      std::vector<std::string> after{kDataset};
      for (const Step& s : steps) after.push_back(s.id());
      steps.push_back(report_step(study, runs, after, dataset_fp, actions_));
    }
    runner.run(steps);
    const StepStatus r = runner.status("report");
    if (report && top && (r == StepStatus::Ran || r == StepStatus::Current))
      result_.report = (fs::path(study.output) / run_layout::kReportFolder / run_layout::kReport).string();
  }

  const StudyActions& actions_;
  const StudyOptions& options_;
  StudyResult& result_;
  std::set<std::string> running_, finished_;
};

}  // namespace

bool StudyResult::ok() const { return count(StepStatus::Failed) == 0 && count(StepStatus::Blocked) == 0; }

std::size_t StudyResult::count(StepStatus status) const {
  return static_cast<std::size_t>(
      std::count_if(steps.begin(), steps.end(), [&](const StepOutcome& o) { return o.status == status; }));
}

StudyResult run_study(const std::string& path, const std::vector<std::string>& sets, const StudyActions& actions,
                      const StudyOptions& options) {
  if (options.lanes < 1) throw UsageError("--lanes: expected 1 or more, got " + std::to_string(options.lanes));
  if (options.lanes > 1 && options.force)
    throw UsageError("--lanes with --force: force runs one at a time (--force --only <run>), or without lanes");
  if (options.lanes > 1 && !options.dry_run && !actions.lane)
    throw Error("layers run: lanes asked for, but this program cannot start them");
  StudyResult result;
  StudyOrder order(actions, options, result);
  order.run_file(path, sets, true);
  return result;
}

}  // namespace layers::study
