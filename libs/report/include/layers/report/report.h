// layers/report/report.h -- `layers report`: one folder a person reads and
// a program diffs, made from finished run folders (run_results.h).
//
// <out>/report.md      the report: models table, accuracy against speed
//                      with the Pareto front, rollout charts with
//                      divergence, per garment type, ground truth beside
//                      predictions, notes on anything missing
// <out>/summary.csv, summary.json, per_type.csv, by_step.csv, bench.csv
//                      the tables (tables.h); seeds.csv (seeds.h);
//                      paired.csv (paired.h)
// <out>/charts/        PNG charts with their gnuplot scripts and data
// <out>/viewer/        the viewer: ground truth and rollouts played side by
//                      side in the browser (viewer.h)
//
// Selection: each run says which split chose its checkpoint and which it
// is evaluated on; a run whose checkpoint was chosen on the test split or
// on the split it is evaluated on is marked in report.md and listed in
// ReportResult::selection_flags (run_results.h selection_flag). A run
// folder holding seed-<s> folders stands for those (expand_seed_folders).
//
// Missing pieces (a run without evaluation or bench.json, no gnuplot, a
// chart gnuplot failed on, no ground truth for the picture) never stop the
// report: they are listed in report.md and in ReportResult::problems. Every
// file is written atomically (temporary name, then rename).
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "layers/report/frames_picture.h"
#include "layers/report/run_results.h"
#include "layers/report/viewer.h"

namespace layers::report {

struct ReportInputs {
  std::vector<std::string> runs;  // run folders (run.output of experiments, or folders of seed-<s> runs)
  std::string title = "layers report";
  std::string split;                // eval-<split> to read (default: see load_run)
  std::string gnuplot = "gnuplot";  // program, a path or a name on PATH
  bool charts = true;               // false: tables and report.md only
  // Row -> the row it is also compared with, paired per sequence
  // (paired.h; every learned row is compared with the reference rows).
  std::map<std::string, std::string> partners;
  PictureOptions picture;  // the picture's and the viewer's rows and sequence
  ViewerOptions viewer;
};

struct ReportResult {
  std::string report;                        // path of report.md
  std::vector<std::string> files;            // every file written, report.md included
  std::vector<std::string> charts;           // the PNGs drawn
  std::string viewer;                        // path of viewer/index.html, "" when none
  std::vector<std::string> problems;         // missing pieces, as in report.md
  std::vector<std::string> selection_flags;  // "<run>: <why>" for each run marked for its selection
  std::vector<std::string> pareto_front;     // run names on the front, fastest first
  std::size_t runs_with_metrics = 0;
};

// Loads the runs and writes the report into out_dir (created if needed).
// Throws only when out_dir cannot be written.
ReportResult write_report(const ReportInputs& inputs, const std::string& out_dir);

// The same for runs already loaded (inputs.runs is not read).
ReportResult write_report(const std::vector<RunResults>& runs, const ReportInputs& inputs, const std::string& out_dir);

}  // namespace layers::report
