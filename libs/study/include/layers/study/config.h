// layers/study/config.h -- the study file of `layers run` (docs/studies.md):
// its typed sections and load_study(), which checks names, steps and
// files.
//
//   name: compare_tiny
//   output: runs/compare_tiny          # study folder; run <name> -> <output>/<name>
//   requires: []                       # study files run first (their checkpoints are used here)
//   dataset: {config: ../data/tiny.yaml, folder: data/tiny, set: [], threads: 2}
//   steps: [train, eval, bench, report]
//   set: [run.threads=2]               # overrides for every experiment
//   seeds: 1                           # repetitions of every experiment (run.seed, +1, ...)
//   eval: {splits: [test], checkpoint: best}
//   bench: {levels: 1, min_time: 0.3, train: true, far_body: false}
//   report: {title: ..., split: test, charts: true, frames: 4, sequence: ""}
//   experiments:
//     - {name: layersnet, file: ../experiments/layersnet_tiny.yaml, set: [train.epochs=2]}
//     - {name: deepsd_stab, file: ..., checkpoint: runs/compare_small/deepsd}
//     - {name: mgnet, file: ..., seeds: 3}  # runs mgnet/seed-0, seed-1, seed-2
//
// An experiment repeated over N seeds (its `seeds`, else the study's) is N
// runs <output>/<name>/seed-<s>, s = its run.seed + k for k = 0..N-1, each
// with run.seed = s; with one seed it is the run <output>/<name>.
// dataset.config may be omitted: dataset.folder is then a finished dataset,
// used as it is and never generated.
//
// File references (requires, dataset.config, experiments[].file) are
// relative to the study file, like `include:`; folders (output,
// dataset.folder, checkpoint) are relative to the working directory, like
// an experiment's data.dataset.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "layers/core/config.h"
#include "layers/train/bench.h"

namespace layers::study {

struct StudyDataset {
  std::string config;            // generator config (configs/data/*.yaml), relative to the study file;
                                 // "" = folder is a finished dataset used as it is (never generated)
  std::string folder;            // dataset folder, relative to the working directory
  std::vector<std::string> set;  // generator overrides, key.path=value
  int threads = 2;               // scenes simulated in parallel

  template <class V>
  void visit(V& v) {
    v("config", config,
      cfg::opt().help("generator config, relative to the study file (omit to use a finished dataset as it is)"));
    v("folder", folder, cfg::opt().required().help("dataset folder (generated when missing or incomplete)"));
    v("set", set, cfg::opt().help("generator overrides key.path=value"));
    v("threads", threads, cfg::opt().range(1, 256).help("scenes generated in parallel"));
  }
};

struct StudyExperiment {
  std::string name;                // run folder <output>/<name>; the run's label in reports
  std::string file;                // experiment config, relative to the study file
  std::vector<std::string> set;    // overrides after the study's `set`
  std::vector<std::string> steps;  // empty: the study's steps
  std::string checkpoint;          // a run folder or checkpoint file to evaluate instead of training
  int seeds = 0;                   // repetitions over seeds; 0: the study's `seeds`

  template <class V>
  void visit(V& v) {
    v("name", name, cfg::opt().required().help("run name (letters, digits, _ - + .)"));
    v("file", file, cfg::opt().required().help("experiment config, relative to the study file"));
    v("set", set, cfg::opt().help("overrides key.path=value"));
    v("steps", steps, cfg::opt().help("steps of this experiment (default: the study's)"));
    v("checkpoint", checkpoint,
      cfg::opt().help("run folder (its checkpoint-<eval.checkpoint>.pt) or .pt file to evaluate; no training"));
    v("seeds", seeds,
      cfg::opt().range(0, 1000).help("repetitions over seeds, runs <name>/seed-<s> (0: the study's seeds)"));
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

struct StudyReport {
  std::string title;  // default: the study name
  std::string split;  // eval-<split> to report (default: the report's own choice)
  bool charts = true;
  int frames = 4;        // columns of the ground truth / predictions picture
  std::string sequence;  // sequence of the picture (default: the report's choice)
  // Experiment -> the experiment it is also compared with, paired per
  // sequence (layers/report/paired.h): e.g. the paper's partner of a row.
  std::map<std::string, std::string> partners;

  template <class V>
  void visit(V& v) {
    v("title", title);
    v("split", split);
    v("charts", charts);
    v("frames", frames, cfg::opt().range(1, 12));
    v("sequence", sequence);
    v("partners", partners,
      cfg::opt().help("experiment -> experiment it is also compared with per sequence (paired, 95% interval)"));
  }
};

// A study's bench defaults, lighter than `layers bench`'s (a study times
// every run): levels 1, min_time 0.3 s, train true, far_body false.
train::BenchOptions study_bench();

struct StudyConfig {
  std::string name;                    // default: the file's stem
  std::string output;                  // default: runs/<name>
  std::vector<std::string> requires_;  // key `requires`
  StudyDataset dataset;
  std::vector<std::string> steps{"train", "eval", "report"};
  std::vector<std::string> set;
  int seeds = 1;  // repetitions of each experiment over seeds (an experiment's own `seeds` wins)
  StudyEval eval;
  train::BenchOptions bench = study_bench();
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
    v("seeds", seeds,
      cfg::opt().range(1, 1000).help("repetitions of every experiment over seeds: run.seed, run.seed+1, ..."));
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

}  // namespace layers::study
