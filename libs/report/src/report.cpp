// `layers report`: loading runs, writing tables, charts and report.md
// (see report.h).
#include "layers/report/report.h"

#include <filesystem>
#include <optional>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/data/run_layout.h"
#include "layers/report/charts.h"
#include "layers/report/gnuplot.h"
#include "layers/report/seeds.h"
#include "layers/report/tables.h"
#include "markdown.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;

// Runs one chart step; a failure becomes the section's `missing` text.
template <typename Draw>
void draw(ChartSection& section, std::vector<std::string>& problems, const std::string& what, Draw&& drawer) {
  try {
    drawer(section.charts);
  } catch (const std::exception& e) {
    section.missing = e.what();
    problems.push_back(what + ": " + e.what());
  }
}

}  // namespace

ReportResult write_report(const ReportInputs& inputs, const std::string& out_dir) {
  std::vector<RunResults> runs;
  for (const std::string& dir : expand_seed_folders(inputs.runs)) runs.push_back(load_run(dir, inputs.split));
  return write_report(runs, inputs, out_dir);
}

ReportResult write_report(const std::vector<RunResults>& runs, const ReportInputs& inputs, const std::string& out_dir) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir))
    throw InputError::message(out_dir, "", "cannot create the report folder" + (ec ? ": " + ec.message() : ""));
  ReportResult result;
  ReportContent content;
  content.title = inputs.title;
  content.runs = runs;
  if (runs.empty()) content.problems.push_back("no run folders given");
  for (const RunResults& r : runs) {
    result.runs_with_metrics += r.eval ? 1 : 0;
    for (const std::string& p : r.problems) content.problems.push_back(r.dir + ": " + p);
    const std::string flag = selection_flag(r);
    if (!flag.empty()) result.selection_flags.push_back(r.name + ": " + flag);
  }

  auto write = [&](const std::string& name, const std::string& text) {
    const std::string path = (fs::path(out_dir) / name).string();
    write_text_atomic(path, text);
    result.files.push_back(path);
  };
  write("summary.csv", summary_csv(runs));
  write("per_type.csv", per_type_csv(runs));
  write("by_step.csv", by_step_csv(runs));
  write("bench.csv", bench_csv(runs));
  write("seeds.csv", seeds_csv(runs));
  std::vector<std::string> unpaired;
  content.paired = paired_comparisons(runs, inputs.partners, &unpaired);
  for (const std::string& u : unpaired) content.problems.push_back("paired comparisons: " + u);
  write("paired.csv", paired_csv(content.paired));
  std::vector<std::string> references;
  curve_references(runs, &references);
  content.problems.insert(content.problems.end(), references.begin(), references.end());

  const std::string charts_dir = (fs::path(out_dir) / content.charts_dir).string();
  std::optional<Gnuplot> gp;
  if (!inputs.charts) {
    content.speed.missing = content.by_step.missing = content.per_type.missing = content.frames.missing =
        content.learning.missing = "charts were switched off";
  } else if (result.runs_with_metrics == 0) {
    content.speed.missing = content.by_step.missing = content.per_type.missing = content.frames.missing =
        content.learning.missing = "no run has an evaluation";
  } else {
    try {
      gp = Gnuplot::find(inputs.gnuplot);
      fs::create_directories(charts_dir);
    } catch (const std::exception& e) {
      content.speed.missing = content.by_step.missing = content.per_type.missing = content.frames.missing =
          content.learning.missing = e.what();
      content.problems.push_back(std::string("charts: ") + e.what());
    }
  }
  if (gp) {
    draw(content.speed, content.problems, "accuracy-against-speed chart",
         [&](std::vector<Chart>& out) { out.push_back(speed_accuracy_chart(*gp, charts_dir, runs)); });
    draw(content.by_step, content.problems, "rollout charts",
         [&](std::vector<Chart>& out) { out = by_step_charts(*gp, charts_dir, runs); });
    draw(content.per_type, content.problems, "per-type chart",
         [&](std::vector<Chart>& out) { out.push_back(per_type_chart(*gp, charts_dir, runs)); });
    draw(content.learning, content.problems, "learning curves",
         [&](std::vector<Chart>& out) { out.push_back(learning_curves_chart(*gp, charts_dir, runs)); });
    draw(content.frames, content.problems, "ground truth and predictions picture", [&](std::vector<Chart>& out) {
      out.push_back(frames_picture(*gp, charts_dir, runs, inputs.picture, content.problems));
    });
    for (const ChartSection* s :
         {&content.speed, &content.by_step, &content.per_type, &content.frames, &content.learning})
      for (const Chart& c : s->charts) result.charts.push_back((fs::path(charts_dir) / c.file).string());
  }

  if (result.runs_with_metrics == 0) {
    content.viewer_missing = "no run has an evaluation";
  } else {
    try {
      const Viewer viewer = write_viewer(runs, inputs.picture, inputs.viewer, out_dir, content.problems);
      result.viewer = viewer.page;
      result.files.insert(result.files.end(), viewer.files.begin(), viewer.files.end());
      content.viewer_page = fs::relative(viewer.page, out_dir).string();
      std::string shown;
      for (const std::string& r : viewer.rows) shown += (shown.empty() ? "" : ", ") + r;
      content.viewer_caption = "Sequence `" + viewer.sequence + "`, frames 0-" + std::to_string(viewer.frames - 1) +
                               " of " + std::to_string(viewer.sequence_frames) + ", side by side: " + shown +
                               "; with play/pause, a frame slider and each row's metrics at the current frame.";
    } catch (const std::exception& e) {
      content.viewer_missing = e.what();
      if (inputs.viewer.enabled) content.problems.push_back(std::string("viewer: ") + e.what());
    }
  }

  std::vector<std::string> chart_files;
  for (const std::string& c : result.charts) chart_files.push_back(fs::relative(c, out_dir).string());
  write("summary.json", summary_json(inputs.title, runs, content.problems, chart_files));
  result.report = (fs::path(out_dir) / data::run_layout::kReport).string();
  write(data::run_layout::kReport, report_markdown(content));
  for (std::size_t i : runs_front_order(runs)) result.pareto_front.push_back(runs[i].name);
  result.problems = content.problems;
  result.files.insert(result.files.end(), result.charts.begin(), result.charts.end());
  return result;
}

}  // namespace layers::report
