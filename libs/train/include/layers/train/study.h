// layers/train/study.h -- `layers run <study.yaml>`: one command for a whole
// study (a dataset, a list of experiments, the steps to run on each),
// skipping every step whose outputs are current (docs/studies.md).
//
//   name: compare_tiny
//   output: runs/compare_tiny          # study folder; run <name> -> <output>/<name>
//   requires: []                       # study files run first (their checkpoints are used here)
//   dataset: {config: ../data/tiny.yaml, folder: data/tiny, set: [], threads: 2}
//   steps: [train, eval, bench, report]
//   set: [run.threads=2]               # overrides for every experiment
//   eval: {splits: [test], checkpoint: best}
//   bench: {levels: 1, min_time: 0.3, train: true, far_body: false}
//   report: {title: ..., split: test, charts: true, frames: 4, sequence: ""}
//   experiments:
//     - {name: layersnet, file: ../experiments/layersnet_tiny.yaml, set: [train.epochs=2]}
//     - {name: deepsd_stab, file: ..., checkpoint: runs/compare_small/deepsd}
//
// dataset.config may be omitted: dataset.folder is then a finished dataset,
// used as it is and never generated.
//
// File references (requires, dataset.config, experiments[].file) are
// relative to the study file, like `include:`; folders (output,
// dataset.folder, checkpoint) are relative to the working directory, like
// an experiment's data.dataset. Every experiment gets run.output =
// <output>/<name> and data.dataset = dataset.folder (after its own `set:`).
//
// Skipping: each step records in <run>/steps.yaml (the report in
// <output>/steps.yaml) a fingerprint of its inputs -- the resolved
// experiment text, the dataset's files, the checkpoint it used (size and
// modification time) -- and its output files. A step is current when its
// record says done, the inputs' fingerprint is the same and every output
// exists. A train step that was interrupted (record "started" with the same
// inputs) resumes from checkpoint-last.pt.
//
// The work itself is done by StudyActions (apps/layers/verb_run.cpp binds
// them to layers::generate, run_training, run_evaluation, run_bench and
// layers::report), so this part is torch-free and testable on its own.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "layers/core/config.h"
#include "layers/train/experiment_config.h"

namespace layers::train {

struct StudyDataset {
  std::string config;             // generator config (configs/data/*.yaml), relative to the study file;
                                  // "" = folder is a finished dataset used as it is (never generated)
  std::string folder;             // dataset folder, relative to the working directory
  std::vector<std::string> set;   // generator overrides, key.path=value
  int threads = 2;                // scenes simulated in parallel

  template <class V>
  void visit(V& v) {
    v("config", config, cfg::opt().help("generator config, relative to the study file (omit to use a finished dataset as it is)"));
    v("folder", folder, cfg::opt().required().help("dataset folder (generated when missing or incomplete)"));
    v("set", set, cfg::opt().help("generator overrides key.path=value"));
    v("threads", threads, cfg::opt().range(1, 256).help("scenes generated in parallel"));
  }
};

struct StudyExperiment {
  std::string name;                 // run folder <output>/<name>; the run's label in reports
  std::string file;                 // experiment config, relative to the study file
  std::vector<std::string> set;     // overrides after the study's `set`
  std::vector<std::string> steps;   // empty: the study's steps
  std::string checkpoint;           // a run folder or checkpoint file to evaluate instead of training

  template <class V>
  void visit(V& v) {
    v("name", name, cfg::opt().required().help("run name (letters, digits, _ - + .)"));
    v("file", file, cfg::opt().required().help("experiment config, relative to the study file"));
    v("set", set, cfg::opt().help("overrides key.path=value"));
    v("steps", steps, cfg::opt().help("steps of this experiment (default: the study's)"));
    v("checkpoint", checkpoint,
      cfg::opt().help("run folder (its checkpoint-<eval.checkpoint>.pt) or .pt file to evaluate; no training"));
  }
};

struct StudyEval {
  std::vector<std::string> splits;  // empty: the experiment's eval.split (else data.test_split)
  std::string checkpoint = "best";  // best or last

  template <class V>
  void visit(V& v) {
    v("splits", splits, cfg::opt().help("splits or subsets to evaluate (default: the experiment's)"));
    v("checkpoint", checkpoint, cfg::opt().choices({"best", "last"}));
  }
};

struct StudyBench {
  int levels = 1;
  double min_time = 0.3;
  bool train = true;
  bool far_body = false;

  template <class V>
  void visit(V& v) {
    v("levels", levels, cfg::opt().range(0, 4).help("subdivision levels 0..n"));
    v("min_time", min_time, cfg::opt().range(0.01, 60).help("seconds per measurement"));
    v("train", train, cfg::opt().help("also time a training step"));
    v("far_body", far_body, cfg::opt().help("also time with a far-away body copy"));
  }
};

struct StudyReport {
  std::string title;     // default: the study name
  std::string split;     // eval-<split> to report (default: the report's own choice)
  bool charts = true;
  int frames = 4;        // columns of the ground truth / predictions picture
  std::string sequence;  // sequence of the picture (default: the report's choice)

  template <class V>
  void visit(V& v) {
    v("title", title);
    v("split", split);
    v("charts", charts);
    v("frames", frames, cfg::opt().range(1, 12));
    v("sequence", sequence);
  }
};

struct StudyConfig {
  std::string name;                       // default: the file's stem
  std::string output;                     // default: runs/<name>
  std::vector<std::string> requires_;     // key `requires`
  StudyDataset dataset;
  std::vector<std::string> steps{"train", "eval", "report"};
  std::vector<std::string> set;
  StudyEval eval;
  StudyBench bench;
  StudyReport report;
  std::vector<StudyExperiment> experiments;
  std::string source;  // the study file (not a key)

  template <class V>
  void visit(V& v) {
    v("name", name, cfg::opt().help("study name (default: the file name)"));
    v("output", output, cfg::opt().help("study folder (default runs/<name>)"));
    v("requires", requires_, cfg::opt().help("study files run before this one, relative to it"));
    v("dataset", dataset, cfg::opt().required());
    v("steps", steps, cfg::opt().help("train, eval, bench, report"));
    v("set", set, cfg::opt().help("overrides for every experiment"));
    v("eval", eval);
    v("bench", bench);
    v("report", report);
    v("experiments", experiments, cfg::opt().required());
  }
};

// Loads a study file and applies `sets` (key.path=value on the study
// file itself). Paths to files are made relative to the working directory;
// names, steps and duplicate run names are checked (InputError naming the
// file and key).
StudyConfig load_study(const std::string& path, const std::vector<std::string>& sets = {});

// One experiment of a study, resolved.
struct StudyRun {
  std::string name, dir;          // dir = <output>/<name>
  ExperimentConfig config;        // with run.output = dir, data.dataset = the study's folder
  std::string config_yaml;        // the resolved experiment (saved as <dir>/experiment.yaml)
  std::vector<std::string> steps; // train, eval, bench (report is the study's)
  std::vector<std::string> eval_splits;
  std::string checkpoint;         // the checkpoint file eval and bench use
  bool external_checkpoint = false;  // from StudyExperiment::checkpoint (no train step)
};

// Reads every experiment of the study (InputError for a bad file or set).
std::vector<StudyRun> resolve_runs(const StudyConfig& study);

// The work of each step; the study decides only what to run.
struct StudyActions {
  // Makes dataset.folder complete (generating what is missing); returns
  // true when it generated anything. `config` is the resolved path.
  std::function<bool(const StudyDataset& dataset)> dataset;
  std::function<void(const StudyRun& run, bool resume)> train;
  std::function<void(const StudyRun& run, const std::string& split)> eval;  // -> <dir>/eval-<split>/
  std::function<void(const StudyRun& run, const StudyBench& bench)> bench;  // -> <dir>/bench.json
  std::function<void(const StudyConfig& study, const std::vector<std::string>& run_dirs, const std::string& out)>
      report;  // -> <out>/report.md
};

struct StudyOptions {
  std::vector<std::string> only;  // run only these experiments (the report step is then left out)
  bool force = false;             // rerun every selected step
  bool dry_run = false;           // print what would run, run nothing
};

enum class StepStatus { Ran, Current, WouldRun, Failed, Blocked };

struct StepOutcome {
  std::string study, run, step;  // run is empty for the dataset and report steps
  StepStatus status = StepStatus::Ran;
  double seconds = 0;
  std::string message;  // why it ran, or the error
};

struct StudyResult {
  std::vector<StepOutcome> steps;  // required studies' steps first
  std::string report;              // <output>/report/report.md when the report step ran or was current
  bool ok() const;
  std::size_t count(StepStatus status) const;
};

// Runs the study file (after the studies it requires, each once), one step
// at a time, printing one line per step ("<run> <step>: current, skipped").
// A failing step is reported and blocks only what depends on it; the other
// runs go on. `sets` apply to this file only.
StudyResult run_study(const std::string& path, const std::vector<std::string>& sets, const StudyActions& actions,
                      const StudyOptions& options);

// Fingerprints (64-bit FNV-1a, 16 hex digits) used in steps.yaml.
std::string fingerprint_text(const std::string& text);
// "<size>:<mtime in ns>" of a file; "missing" when it does not exist.
std::string file_stamp(const std::string& path);
// The dataset folder's dataset.yaml, splits.yaml, stats.h5 and shards.
std::string dataset_fingerprint(const std::string& folder);

}  // namespace layers::train
