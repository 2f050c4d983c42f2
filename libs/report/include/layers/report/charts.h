// layers/report/charts.h -- the report's metric charts, drawn by gnuplot
// into one folder with their scripts and data files:
//
//   speed_accuracy   error (mm) against ms per frame (log x) for every run
//                    with an evaluation, the Pareto front marked and
//                    labelled; one more point per benchmarked scene size
//                    when the run has a bench.json
//   by_step_<key>    each registered metric (layers/metrics/registry.h:
//                    by_step_error_mm, by_step_h_collision, ...) against
//                    the rollout step for every run,
//                    each run's first divergence marked; a metric no run
//                    has (e.g. evaluations from before it was measured) is
//                    not drawn
//   per_type         error bars (mean +- std over sequences) per garment
//                    type for every run
//   learning_curves  validation error per epoch against training windows
//                    seen, for every trained run
//
// Each run keeps one colour in every chart (its position in the list).
// The functions throw layers::Error when gnuplot fails or nothing can be
// drawn (e.g. no run has a measured speed); the report records the message.
#pragma once

#include <string>
#include <vector>

#include "layers/report/gnuplot.h"
#include "layers/report/run_results.h"

namespace layers::report {

struct Chart {
  std::string file;  // PNG file name inside the charts folder
  std::string title;
  std::string caption;  // what the chart shows (Markdown), for report.md
};

Chart speed_accuracy_chart(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs);
// One chart per metric that some run has values for (error, H, L).
std::vector<Chart> by_step_charts(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs);
Chart per_type_chart(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs);
// Validation error per epoch against the windows seen (each run's
// selection.json); throws when no run has one.
Chart learning_curves_chart(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs);

// The colour of the i-th run ("#rrggbb").
std::string run_color(std::size_t i);

}  // namespace layers::report
