// The report's metric charts: accuracy against speed, metrics against the
// rollout step, per garment type bars (see charts.h).
#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/metrics/registry.h"
#include "layers/report/charts.h"
#include "layers/report/tables.h"
#include "text.h"

namespace layers::report {
namespace {

// A number for a gnuplot data file (NaN is declared missing in the scripts).
std::string datum(double v) { return std::isfinite(v) ? exact(v) : "NaN"; }

// A double-quoted string column for a gnuplot data file.
std::string data_label(const std::string& s) {
  std::string out = "\"";
  for (char c : s) out += c == '"' ? '\'' : c;
  return out + "\"";
}

void write_data(const std::string& dir, const std::string& file, const std::string& text) {
  write_text_atomic(dir + "/" + file, text);
}

bool measured(double ms) { return std::isfinite(ms) && ms > 0; }

}  // namespace

std::string run_color(std::size_t i) {
  static const char* palette[] = {"#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
                                  "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
  return palette[i % (sizeof palette / sizeof *palette)];
}

Chart speed_accuracy_chart(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs) {
  const std::string name = "speed_accuracy";
  const std::vector<bool> front = runs_on_front(runs);
  std::ostringstream points, front_data, bench;
  std::vector<std::string> plots, unmeasured;
  std::size_t blocks = 0, bench_blocks = 0;
  std::ostringstream bench_plots;
  std::vector<std::size_t> placed;  // the runs with a point on the chart
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResults& r = runs[i];
    if (!r.eval) continue;
    const double error = r.eval->overall.get(metrics::kError).mean;
    if (!measured(r.eval->ms_per_frame) || !std::isfinite(error)) {
      unmeasured.push_back(r.name);
      continue;
    }
    placed.push_back(i);
    points << datum(r.eval->ms_per_frame) << ' ' << datum(error) << ' '
           << data_label(r.name + (front[i] ? " [front]" : "")) << "\n\n\n";
    plots.push_back(gnuplot_string(name + "_runs.dat") + " index " + std::to_string(blocks++) +
                    " using 1:2 with points pt 7 ps 1.8 lc rgb " + gnuplot_string(run_color(i)) + " title " +
                    gnuplot_string(r.name));
    if (!r.bench) continue;
    std::size_t rows = 0;
    for (const BenchPoint& b : r.bench->rows) {
      if (b.far_body || !measured(b.ms_per_frame)) continue;
      bench << datum(b.ms_per_frame) << ' ' << datum(error) << ' '
            << data_label(std::to_string(b.garment_vertices) + " v") << '\n';
      ++rows;
    }
    if (rows == 0) continue;
    bench << "\n\n";
    bench_plots << ", \\\n     " << gnuplot_string(name + "_bench.dat") << " index " << bench_blocks
                << " using 1:2 with linespoints pt 4 ps 1.2 dt 3 lc rgb " << gnuplot_string(run_color(i)) << " title "
                << gnuplot_string(r.name + ": benchmarked sizes") << ", \\\n     "
                << gnuplot_string(name + "_bench.dat") << " index " << bench_blocks
                << " using 1:2:3 with labels rotate by -35 left offset char 0.2,-0.8 font ',8' tc rgb "
                << gnuplot_string(run_color(i)) << " notitle";
    ++bench_blocks;
  }
  if (blocks == 0) throw Error("no run has both an error and a measured ms per frame: nothing to place on the chart");
  for (std::size_t i : runs_front_order(runs))
    front_data << datum(runs[i].eval->ms_per_frame) << ' ' << datum(runs[i].eval->overall.get(metrics::kError).mean)
               << '\n';
  write_data(dir, name + "_runs.dat", "# ms_per_frame error_mm label; one block per run\n" + points.str());
  write_data(dir, name + "_front.dat", "# the Pareto front, fastest first: ms_per_frame error_mm\n" + front_data.str());
  if (bench_blocks)
    write_data(dir, name + "_bench.dat", "# ms_per_frame error_mm label; one block per run\n" + bench.str());

  std::ostringstream s;
  s << gp.preamble(name, 900, 600) << "set title 'Accuracy against speed'\n"
    << "set xlabel 'ms per predicted frame (log scale)'\nset ylabel 'mean Euclidean error (mm)'\n"
    << "set logscale x\nset yrange [0:*]\nset grid\nset key outside right top\nset datafile missing 'NaN'\n"
    << "set offsets graph 0.15, graph 0.35, graph 0.15, graph 0.15\n"
    << "plot " << gnuplot_string(name + "_front.dat")
    << " using 1:2 with steps dt 2 lw 1.5 lc rgb '#999999' title 'Pareto front', \\\n     "
    << gnuplot_string(name + "_front.dat") << " using 1:2 with points pt 6 ps 3.2 lw 2 lc rgb '#d62728' title "
    << "'on the front'";
  for (const std::string& p : plots) s << ", \\\n     " << p;
  s << ", \\\n     " << gnuplot_string(name + "_runs.dat")
    << " using 1:2:3 with labels offset char 1.5,0.9 left notitle" << bench_plots.str() << "\n";
  gp.plot(dir, name, s.str());

  std::string caption =
      "Each point is one run: its mean Euclidean error over " + evaluated_sequences(runs, placed) +
      " (mm) against the time its model took per predicted frame during evaluation (ms, log scale). Lower "
      "and further left is better. "
      "Runs circled in red and marked [front] are on the Pareto front: no other run is at least as fast "
      "and as accurate while better in one of the two; the dashed staircase bounds the region they dominate.";
  if (bench_blocks)
    caption +=
        " Dotted lines: the same run's `layers bench` timings on larger scenes (garments subdivided, "
        "labelled with their vertex count), plotted at the run's evaluated error -- they show how its "
        "cost grows with the scene, not a new accuracy.";
  if (!unmeasured.empty()) {
    caption += " Left out (no measured speed or error):";
    for (const std::string& n : unmeasured) caption += " " + n;
    caption += ".";
  }
  return {name + ".png", "Accuracy against speed", caption};
}

std::vector<Chart> by_step_charts(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs) {
  // One chart per registered metric; shares drawn as percentages.
  const std::vector<metrics::MetricDef>& defs = metrics::registered();
  const auto scale = [](const metrics::MetricDef& d) { return d.unit == metrics::Unit::Share ? 100.0 : 1.0; };

  // One data file for all metrics: a block per run with steps.
  std::ostringstream data;
  data << "# step";
  for (const metrics::MetricDef& d : defs) data << ' ' << d.key << (d.unit == metrics::Unit::Share ? "_%" : "");
  data << "; one block per run\n";
  std::vector<std::size_t> plotted;
  std::int64_t last_step = 1;
  bool diverged = false;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!runs[i].eval || runs[i].eval->by_step.empty()) continue;
    for (const StepMetrics& st : runs[i].eval->by_step) {
      data << st.step;
      for (const metrics::MetricDef& d : defs) data << ' ' << datum(scale(d) * st.get(d.key));
      data << '\n';
      last_step = std::max(last_step, st.step);
    }
    data << "\n\n";
    plotted.push_back(i);
    diverged = diverged || runs[i].eval->first_divergence_step() >= 0;
  }
  if (plotted.empty()) throw Error("no run has per-step metrics (metrics.json by_step): no rollout charts");
  write_data(dir, "by_step.dat", data.str());

  std::vector<Chart> charts;
  for (std::size_t m = 0; m < defs.size(); ++m) {
    const metrics::MetricDef& metric = defs[m];
    bool any = false;
    for (std::size_t i : plotted)
      for (const StepMetrics& st : runs[i].eval->by_step) any = any || std::isfinite(st.get(metric.key));
    if (!any) continue;
    const std::string name = "by_step_" + metric.key;
    const std::string title = metric.label + " against rollout step";
    const bool bound = metric.diverged == metrics::Diverged::Bound;
    std::ostringstream s;
    s << gp.preamble(name, 900, 500) << "set title " << gnuplot_string(title) << "\n"
      << "set xlabel 'rollout step (predicted frames after the ground-truth start)'\n"
      << "set ylabel " << gnuplot_string(metric.axis) << "\nset grid\nset key outside right top\n"
      << "set datafile missing 'NaN'\nset xrange [1:" << std::max<std::int64_t>(last_step, 2) << "]\n"
      << (bound && diverged ? "set logscale y\n" : "set yrange [0:*]\n");
    for (std::size_t i : plotted) {
      const std::int64_t step = runs[i].eval->first_divergence_step();
      if (step < 0) continue;
      s << "set arrow from " << step << ", graph 0 to " << step << ", graph 1 nohead dt 2 lw 1.5 lc rgb "
        << gnuplot_string(run_color(i)) << "\n"
        << "set label " << gnuplot_string(runs[i].name + " diverges (step " + std::to_string(step) + ")") << " at "
        << step << ", graph 0.98 right rotate by 90 offset char -1.2,0 tc rgb " << gnuplot_string(run_color(i)) << "\n";
    }
    // The ground truth's own value (mean over sequences) for reference.
    double truth = kAbsent;
    for (std::size_t i : plotted)
      if (metric.truth && !std::isfinite(truth)) truth = runs[i].eval->truth_of(metric.key);
    s << "plot ";
    if (std::isfinite(truth))
      s << exact(scale(metric) * truth) << " with lines dt 3 lw 1.5 lc rgb '#555555' title 'ground truth', \\\n     ";
    for (std::size_t k = 0; k < plotted.size(); ++k) {
      const std::size_t i = plotted[k];
      s << (k ? ", \\\n     " : "") << "'by_step.dat' index " << k << " using 1:" << m + 2 << " with lines lw 2 lc rgb "
        << gnuplot_string(run_color(i)) << " title " << gnuplot_string(runs[i].name);
    }
    s << "\n";
    gp.plot(dir, name, s.str());
    std::string caption = "Mean over " + evaluated_sequences(runs, plotted) + " of the " + metric.label + " (" +
                          metric.description +
                          ") at each rollout step: the model's own predictions are fed back, the body and wind "
                          "stay ground truth, so growth along the x axis is accumulated drift." +
                          (metric.truth ? " The dotted grey line is the ground truth's own value (mean over the "
                                          "first run's sequences): the simulator's data is not perfect either."
                                        : "");
    if (diverged)
      caption +=
          " A dashed vertical line marks the first step at which any sequence of that run diverged "
          "(non-finite or above the error bound); from there " +
          std::string(bound ? "it counts as the bound (log y axis)." : "it is left out.");
    charts.push_back({name + ".png", title, caption});
  }
  return charts;
}

Chart per_type_chart(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs) {
  const std::string name = "per_type";
  std::set<std::string> types;
  std::vector<std::size_t> plotted;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    if (!runs[i].eval || runs[i].eval->per_type.empty()) continue;
    plotted.push_back(i);
    for (const auto& [type, m] : runs[i].eval->per_type) types.insert(type);
  }
  if (plotted.empty()) throw Error("no run has per garment type metrics: no per-type chart");
  std::ostringstream data;
  data << "# type, then error_mm mean and std per run:";
  for (std::size_t i : plotted) data << ' ' << runs[i].name;
  data << '\n';
  for (const std::string& type : types) {
    data << data_label(type);
    for (std::size_t i : plotted) {
      const auto& pt = runs[i].eval->per_type;
      auto it = std::find_if(pt.begin(), pt.end(), [&](const auto& p) { return p.first == type; });
      const Stat s = it == pt.end() ? Stat{} : it->second.get(metrics::kError);
      data << ' ' << datum(s.mean) << ' ' << datum(std::isfinite(s.std) ? s.std : 0.0);
    }
    data << '\n';
  }
  write_data(dir, name + ".dat", data.str());
  const int width = static_cast<int>(std::clamp<std::size_t>(200 + 60 * types.size() * plotted.size(), 700, 1600));
  std::ostringstream s;
  s << gp.preamble(name, width, 500) << "set title 'Error per garment type'\n"
    << "set ylabel 'mean Euclidean error (mm), +- std over sequences'\nset grid ytics\n"
    << "set key outside right top\nset datafile missing 'NaN'\nset style data histograms\n"
    << "set style histogram errorbars gap 2 lw 1\nset style fill solid 0.85 border rgb '#333333'\n"
    << "set boxwidth 0.9\nset yrange [0:*]\nset xtics nomirror\nplot ";
  for (std::size_t k = 0; k < plotted.size(); ++k)
    s << (k ? ", \\\n     " : "") << gnuplot_string(name + ".dat") << " using " << 2 + 2 * k << ':' << 3 + 2 * k
      << (k == 0 ? ":xtic(1)" : "") << " lc rgb " << gnuplot_string(run_color(plotted[k])) << " title "
      << gnuplot_string(runs[plotted[k]].name);
  s << "\n";
  gp.plot(dir, name, s.str());
  return {name + ".png", "Error per garment type",
          "For every garment type, each run's mean Euclidean error over " + evaluated_sequences(runs, plotted) +
              " that hold that type (bar) and its standard deviation over those sequences (whisker). Outer "
              "garments (e.g. jacket) ride on the inner ones, so their error includes the inner layer's drift."};
}

Chart learning_curves_chart(const Gnuplot& gp, const std::string& dir, const std::vector<RunResults>& runs) {
  const std::string name = "learning_curves";
  std::ostringstream data, plot;
  std::size_t blocks = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const LearningCurve& c = runs[i].curve;
    std::ostringstream block;
    std::size_t points = 0;
    for (std::size_t k = 0; k < c.val_error_mm.size(); ++k) {
      if (!std::isfinite(c.val_error_mm[k]) || !std::isfinite(c.windows_seen[k])) continue;
      block << datum(c.windows_seen[k]) << ' ' << datum(c.val_error_mm[k]) << '\n';
      ++points;
    }
    if (points == 0) continue;
    data << "# " << runs[i].name << "\n" << block.str() << "\n\n";
    plot << (blocks ? ", \\\n     " : "") << gnuplot_string(name + ".dat") << " index " << blocks << " using 1:2 with "
         << (c.only_best ? "points pt 9 ps 1.6" : "linespoints lw 2 pt 7 ps 0.8") << " lc rgb "
         << gnuplot_string(run_color(i)) << " title "
         << gnuplot_string(runs[i].name + (c.only_best ? " (chosen epoch only)" : ""));
    ++blocks;
  }
  if (blocks == 0) throw Error("no run has a validation error per epoch (selection.json): no learning curves");
  // The reference rows on the same measure: horizontal dashed lines.
  const std::vector<ReferenceLevel> levels = curve_references(runs, nullptr);
  for (std::size_t k = 0; k < levels.size(); ++k) {
    if (!std::isfinite(levels[k].error_mm)) continue;
    plot << ", \\\n     " << datum(levels[k].error_mm) << " with lines dt 2 lw 2 lc rgb "
         << gnuplot_string(k % 2 ? "#555555" : "#000000") << " title "
         << gnuplot_string(levels[k].name + " (reference)");
  }
  write_data(dir, name + ".dat", data.str());
  std::ostringstream s;
  s << gp.preamble(name, 1000, 560) << "set title 'Learning curves'\n"
    << "set xlabel 'training windows seen'\nset ylabel 'validation error (mm)'\nset grid\n"
    << "set key outside right top\nset datafile missing 'NaN'\nplot " << plot.str() << "\n";
  gp.plot(dir, name, s.str());
  return {name + ".png", "Learning curves",
          "Each trained run's validation error at the end of every epoch (the trainer's selection metric, "
          "selection.json) against the training windows seen by then; a run whose record kept only its chosen "
          "epoch is one point. Dashed lines: the reference rows (no trained parameters) evaluated on the same "
          "measure (same split, rollout frames and sequences), where the runs recorded it. A curve still falling "
          "at its last point was stopped before it converged."};
}

}  // namespace layers::report
