// `layers run <study.yaml>`: a whole study -- dataset, then train, eval and
// bench for each experiment, then the report -- skipping the steps whose
// outputs are current (libs/study/include/layers/study/study.h,
// docs/studies.md). This file binds the study's steps to the libraries, all
// in-process: layers::generate for the dataset, layers::train for
// train/eval/bench and layers::report (write_report) for the report; with
// --lanes, runs go to child `layers run --only <run>` processes.
#include <cstdio>
#include <filesystem>
#include <functional>

#include "child_command.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/generate/generator.h"
#include "layers/generate/imported_garment.h"
#include "layers/metrics/registry.h"
#include "layers/report/report.h"
#include "layers/study/study.h"
#include "layers/train/bench.h"
#include "layers/train/evaluator.h"
#include "layers/train/trainer.h"
#include "plugins.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace layers::app {
namespace {

bool make_dataset(const study::StudyDataset& d) {
  if (d.config.empty()) {  // a finished dataset, used as it is
    for (const char* f : {"dataset.yaml", "splits.yaml"})
      if (!fs::is_regular_file(fs::path(d.folder) / f))
        throw InputError(d.folder, "dataset.folder", "a finished dataset (no dataset.config to generate one)",
                         std::string("no ") + f);
    return false;
  }
  const generate::GeneratorConfig config = generate::load_generator_config(d.config, d.set);
  const std::string resolved = cfg::to_yaml(cfg::to_node(config));
  if (generate::dataset_complete(d.folder, config)) {
    const fs::path saved = fs::path(d.folder) / "generator.yaml";
    if (!fs::exists(saved) || !generate::same_saved_config(saved.string(), resolved))
      throw InputError::message(saved.string(), "",
                                "the dataset folder was made with another generator config than " + d.config +
                                    " (with the study's dataset.set); point dataset.folder elsewhere or remove it");
    return false;
  }
  generate::GenerateOptions options;
  options.out = d.folder;
  options.threads = d.threads;
  const generate::GenerateReport r = generate::generate_dataset(config, resolved, options);
  std::printf("  %s: %d scenes simulated (%d written, %d skipped), %d finished before, %.1f s\n", d.folder.c_str(),
              r.simulated, r.written, r.skipped, r.reused, r.seconds);
  if (!r.finalized) throw Error(d.folder + ": the dataset is not complete after generating it");
  return true;
}

study::StudyActions library_actions() {
  study::StudyActions a;
  a.dataset = make_dataset;
  a.train = [](const study::StudyRun& run, bool resume) {
    train::TrainOptions options;
    options.resume = resume;
    const train::TrainReport r = train::run_training(run.config, load_plugins().registry, options);
    std::printf("  %s: %d epochs (%lld steps)%s, %lld trainable parameters\n", run.name.c_str(), r.epochs_done,
                static_cast<long long>(r.steps), resume ? ", resumed" : "",
                static_cast<long long>(r.trainable_parameters));
  };
  a.eval = [](const study::StudyRun& run, const std::string& split) {
    train::EvalOptions options;
    options.checkpoint = run.checkpoint;
    options.split = split;
    const train::EvalReport r = train::run_evaluation(run.config, load_plugins().registry, options);
    std::string values;
    for (const metrics::MetricDef& d : metrics::registered())
      values += ", " + d.key + " " + metrics::format_value(d, r.overall.at(d.key));
    std::printf("  %s on %s:%s, %lld of %lld sequences diverged, %.2f ms/frame\n", run.name.c_str(), split.c_str(),
                values.c_str() + 1, static_cast<long long>(r.diverged), static_cast<long long>(r.sequences),
                r.ms_per_frame);
  };
  a.bench = [](const study::StudyRun& run, const train::BenchOptions& options) {
    const train::BenchReport r = train::run_bench(run.config, load_plugins().registry, options);
    if (!r.rows.empty())
      std::printf("  %s: %.2f ms/frame at %lld garment vertices -> %s\n", run.name.c_str(), r.rows.front().ms_per_frame,
                  static_cast<long long>(r.rows.front().garment_vertices), r.out.c_str());
  };
  a.report = [](const study::StudyConfig& study, const std::vector<std::string>& dirs, const std::string& out) {
    report::ReportInputs inputs;
    inputs.runs = dirs;
    inputs.title = study.report.title.empty() ? "Study " + study.name : study.report.title;
    inputs.split = study.report.split;
    inputs.charts = study.report.charts;
    inputs.picture.dataset = study.dataset.folder;
    inputs.picture.sequence = study.report.sequence;
    inputs.picture.frames = study.report.frames;
    inputs.partners = study.report.partners;
    const report::ReportResult r = report::write_report(inputs, out);
    for (const std::string& p : r.problems) std::printf("  report note: %s\n", p.c_str());
    for (const std::string& f : r.selection_flags) std::printf("  report: selection marked: %s\n", f.c_str());
    for (const std::string& c : r.charts) std::printf("  chart: %s\n", c.c_str());
    if (r.runs_with_metrics == 0) throw Error("no run of the study had an evaluation to report (" + r.report + ")");
  };
  return a;
}

}  // namespace

// A lane: this binary as `layers run <file> [--set ...] --only <run>`, its
// output appended to <run>/lane.log.
std::function<bool(const study::StudyRun&)> lane_action(const std::string& file, const std::vector<std::string>& sets,
                                                        const std::string& log_level) {
  std::string command = shell_quote(this_executable("run --lanes")) + " --log-level " + shell_quote(log_level) +
                        " run " + shell_quote(file);
  for (const std::string& s : sets) command += " --set " + shell_quote(s);
  return [command](const study::StudyRun& run) {
    const std::string log = (fs::path(run.dir) / "lane.log").string();
    return run_logged(command + " --only " + shell_quote(run.name), log, true) == 0;
  };
}

VerbRun register_run(CLI::App& app, const Global& global) {
  auto* cmd = app.add_subcommand(
      "run", "Run a study (configs/studies/*.yaml): dataset, train, eval, bench, report; current steps are skipped");
  struct Args {
    std::string file;
    std::vector<std::string> sets;
    study::StudyOptions options;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("study", a->file, "study file")->required()->check(CLI::ExistingFile);
  cmd->add_option("--set", a->sets, "override a value of the study file: --set key.path=value (repeatable)");
  cmd->add_option("--only", a->options.only, "run only this experiment (repeatable; leaves the report out)");
  cmd->add_flag("--force", a->options.force, "rerun every step of this study, current or not");
  cmd->add_flag("--dry-run", a->options.dry_run, "print which steps are current and which would run");
  cmd->add_option("--lanes", a->options.lanes,
                  "run this many of the study's runs at a time, each as `layers run --only <run>` with its log in "
                  "<run>/lane.log (after the dataset step; the report once they end)")
      ->capture_default_str();
  return [a, &global]() {
    study::StudyActions actions = library_actions();
    if (a->options.lanes > 1) actions.lane = lane_action(a->file, a->sets, global.log_level);
    const study::StudyResult r = study::run_study(a->file, a->sets, actions, a->options);
    using S = study::StepStatus;
    std::printf("%zu steps ran, %zu current", r.count(S::Ran), r.count(S::Current));
    if (a->options.dry_run) std::printf(", %zu would run", r.count(S::WouldRun));
    if (r.count(S::Failed) || r.count(S::Blocked))
      std::printf(", %zu FAILED, %zu blocked by a failure", r.count(S::Failed), r.count(S::Blocked));
    std::printf("\n");
    if (!r.report.empty()) std::printf("report: %s\n", r.report.c_str());
    return static_cast<int>(r.ok() ? kOk : kFailure);
  };
}

}  // namespace layers::app
