// `layers report --runs DIR... [--out DIR]`: a Markdown report with CSV/JSON
// tables and gnuplot charts made from finished run folders (see
// libs/report/include/layers/report/report.h). Missing pieces are listed
// on stderr and in report.md; the exit code is 1 only when no run had an
// evaluation to report. A --out folder that holds a report is replaced
// only with --force, which moves it aside first (nothing is overwritten).
#include <cstdio>
#include <filesystem>

#include "layers/core/error.h"
#include "layers/data/run_layout.h"
#include "layers/report/report.h"
#include "output_folder.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_report(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("report", "Write a Markdown report with tables and charts from finished runs");
  struct Args {
    report::ReportInputs inputs;
    std::string out = "report";
    bool no_charts = false, no_viewer = false, force = false;
    std::vector<std::string> partners;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--runs", a->inputs.runs,
                  "run folders (run.output of experiments, evaluated; a folder of seed-<s> runs stands for them)")
      ->required()
      ->expected(1, -1);
  cmd->add_option("--out", a->out, "output folder")->capture_default_str();
  cmd->add_option("--title", a->inputs.title, "report title")->capture_default_str();
  cmd->add_option("--split", a->inputs.split, "read eval-<split>/ (default: eval-test, else the first eval-*)");
  cmd->add_option("--dataset", a->inputs.picture.dataset,
                  "ground truth for the picture (default: each run's data.dataset)");
  cmd->add_option("--sequence", a->inputs.picture.sequence, "sequence of the picture (default: first shared one)");
  cmd->add_option("--frames", a->inputs.picture.frames, "frames (columns) in the picture")
      ->capture_default_str()
      ->check(CLI::Range(1, 12));
  cmd->add_option("--gnuplot", a->inputs.gnuplot, "gnuplot program")->capture_default_str();
  cmd->add_flag("--no-charts", a->no_charts, "tables and report.md only");
  cmd->add_flag("--no-viewer", a->no_viewer, "no viewer/ (the page that plays the rollouts in the browser)");
  cmd->add_option("--three", a->inputs.viewer.three, "three.min.js copied into the viewer (Debian's libjs-three)")
      ->capture_default_str();
  cmd->add_option("--partner", a->partners,
                  "ROW=OTHER: also compare row ROW with OTHER per sequence (paired, 95% interval); every learned row "
                  "is compared with the reference rows");
  cmd->add_flag("--force", a->force,
                "replace a report in --out: the old folder is moved aside to <out>.replaced-<time>, never deleted");
  return [a]() {
    a->inputs.charts = !a->no_charts;
    a->inputs.viewer.enabled = !a->no_viewer;
    for (const std::string& p : a->partners) {
      const std::size_t eq = p.find('=');
      if (eq == std::string::npos || eq == 0 || eq + 1 == p.size())
        throw InputError("layers report", "--partner", "ROW=OTHER (two run or experiment names)", "'" + p + "'");
      a->inputs.partners[p.substr(0, eq)] = p.substr(eq + 1);
    }
    namespace fs = std::filesystem;
    std::error_code ec;
    const bool holds_report = fs::exists(fs::path(a->out) / data::run_layout::kReport, ec);
    if (holds_report && !a->force)
      throw InputError(a->out, "--out", "a new folder, or --force to move the report there aside",
                       std::string("a folder holding a report (") + data::run_layout::kReport + ")");
    std::vector<fs::path> runs(a->inputs.runs.begin(), a->inputs.runs.end());
    if (holds_report) {
      const fs::path aside = move_aside(a->out, "--out");
      std::printf("moved the old report %s aside to %s\n", a->out.c_str(), aside.string().c_str());
    } else {
      // A folder of other files is the user's (issue 62 D1): refused.
      claim_new_output(a->out, "--out", runs);
    }
    const report::ReportResult r = report::write_report(a->inputs, a->out);
    for (const std::string& p : r.problems) std::fprintf(stderr, "layers report: warning: %s\n", p.c_str());
    for (const std::string& f : r.selection_flags)
      std::fprintf(stderr, "layers report: warning: %s (marked in the report)\n", f.c_str());
    std::printf("runs with an evaluation: %zu\n", r.runs_with_metrics);
    std::printf("Pareto front (fastest first):");
    for (const std::string& name : r.pareto_front) std::printf(" %s", name.c_str());
    std::printf("%s\n", r.pareto_front.empty() ? " none" : "");
    for (const std::string& c : r.charts) std::printf("chart: %s\n", c.c_str());
    if (!r.viewer.empty()) std::printf("viewer: %s\n", r.viewer.c_str());
    std::printf("report: %s\n", r.report.c_str());
    if (r.runs_with_metrics == 0) {
      std::fprintf(stderr, "layers report: error: no run folder had an evaluation to report (see %s)\n",
                   r.report.c_str());
      return static_cast<int>(kFailure);
    }
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
