// layers/study/study.h -- `layers run <study.yaml>`: one command for a
// whole study (a dataset, a list of experiments, the steps to run on each),
// skipping every step whose outputs are current (docs/studies.md). The
// study file is config.h, the runs runs.h, the records records.h and the
// step loop runner.h; this part says which steps a study has.
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
// layers::report), so this library is torch-free and testable on its own.
#pragma once

#include <cstddef>
#include <functional>
#include <string>
#include <vector>

#include "layers/study/config.h"
#include "layers/study/runner.h"
#include "layers/study/runs.h"

namespace layers::study {

// The work of each step; the study decides only what to run.
struct StudyActions {
  // Makes dataset.folder complete (generating what is missing); returns
  // true when it generated anything. `config` is the resolved path.
  std::function<bool(const StudyDataset& dataset)> dataset;
  std::function<void(const StudyRun& run, bool resume)> train;
  std::function<void(const StudyRun& run, const std::string& split)> eval;           // -> <dir>/eval-<split>/
  std::function<void(const StudyRun& run, const train::BenchOptions& bench)> bench;  // -> <dir>/bench.json
  std::function<void(const StudyConfig& study, const std::vector<std::string>& run_dirs, const std::string& out)>
      report;  // -> <out>/report.md
  // Lanes (StudyOptions::lanes): runs every step of the run named `run`
  // elsewhere, e.g. in a child `layers run <file> --only <run>`; true when
  // it succeeded. `run` lists where its log goes.
  std::function<bool(const StudyRun& run)> lane;
};

struct StudyOptions {
  std::vector<std::string> only;  // run only these experiments (the report step is then left out)
  bool force = false;             // rerun every selected step
  bool dry_run = false;           // print what would run, run nothing
  // More than 1: after the dataset step, the top study's runs go to
  // StudyActions::lane, this many at a time, and this process then checks
  // them (all current, or blocked where a lane failed) and writes the
  // report. Not with `force`.
  int lanes = 1;
};

struct StudyResult {
  std::vector<StepOutcome> steps;  // required studies' steps first
  std::string report;              // <output>/report/report.md when the report step ran or was current
  bool ok() const;
  std::size_t count(StepStatus status) const;
};

// Runs the study file (after the studies it requires, each once), one step
// at a time (or its runs in lanes), printing one line per step ("<run>
// <step>: current, skipped").
// A failing step is reported and blocks only what depends on it; the other
// runs go on. `sets` apply to this file only.
StudyResult run_study(const std::string& path, const std::vector<std::string>& sets, const StudyActions& actions,
                      const StudyOptions& options);

}  // namespace layers::study
