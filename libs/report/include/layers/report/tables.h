// layers/report/tables.h -- the report's tables for programs, built from
// loaded runs (run_results.h). Rates are shares 0..1 as in metrics.json,
// errors mm, times ms; an empty cell (CSV) or null (JSON) is a value the
// run does not have.
//
// Every registered metric (layers/metrics/registry.h) is a pair of columns
// <key>, <key>_std (mean and std over sequences), in registry order; read
// CSV columns by their header, not by position.
//
//   summary.csv   one row per run: run, model, split, sequences, frames,
//                 parameters, ms_per_frame, each metric, the ground
//                 truth's (truth_<key>, for the metrics measured on it),
//                 diverged, first_divergence_step, pareto, what chose the
//                 checkpoint (checkpoint, chosen_on, evaluated_on,
//                 chosen_epoch, epochs, val_error_mm, selection_flag:
//                 run_results.h selection_flag) and the seed columns
//                 (experiment, seed: empty unless a seed-<s> run)
//   per_type.csv  one row per run and garment type: each metric
//   by_step.csv   one row per run and rollout step: each metric's mean
//   bench.csv     one row per run and benchmarked scene size
//   summary.json  all of the above but by_step, plus what each metric is
//                 (`metrics`: key, unit, better, scope, rule), the Pareto
//                 front in speed order, the experiments over seeds
//                 (seeds.h), the problems met and the charts made
#pragma once

#include <string>
#include <vector>

#include "layers/report/run_results.h"

namespace layers::report {

// Pareto membership of each run: eval's ms_per_frame against the overall
// error (pareto.h); false for a run without an evaluation.
std::vector<bool> runs_on_front(const std::vector<RunResults>& runs);
// Indices of the runs on the front, fastest first.
std::vector<std::size_t> runs_front_order(const std::vector<RunResults>& runs);

std::string summary_csv(const std::vector<RunResults>& runs);
std::string per_type_csv(const std::vector<RunResults>& runs);
std::string by_step_csv(const std::vector<RunResults>& runs);
std::string bench_csv(const std::vector<RunResults>& runs);
std::string summary_json(const std::string& title, const std::vector<RunResults>& runs,
                         const std::vector<std::string>& problems, const std::vector<std::string>& charts);

}  // namespace layers::report
