// `layers eval <experiment.yaml>`: roll the trained model out on a split
// and write metrics.json, sequences.csv and predictions.h5 (see
// libs/train/include/layers/train/evaluator.h). Data-parallel under
// `layers launch` or srun (dist_join.h): the sequences are split over the
// ranks and rank 0 writes and prints the same results one process would.
#include <cmath>
#include <cstdio>

#include "config_loading.h"
#include "dist_join.h"
#include "layers/data/run_layout.h"
#include "layers/metrics/registry.h"
#include "layers/train/evaluator.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {
namespace {

// One line of the results table: a label, then each registered metric.
void print_row(const std::string& label, const train::MetricSummary& values) {
  std::printf("%-14s", label.c_str());
  for (const metrics::MetricDef& d : metrics::registered())
    std::printf(" %*s", d.unit == metrics::Unit::Millimetre ? 16 : 12,
                metrics::format_value(d, values.at(d.key)).c_str());
  std::printf("\n");
}

}  // namespace

VerbRun register_eval(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("eval", "Evaluate a trained model: rollouts, errors and collision rates");
  struct Args {
    ConfigArgs config;
    train::EvalOptions options;
    bool quiet = false;
  };
  auto a = std::make_shared<Args>();
  add_config_options(*cmd, a->config, /*required=*/true);
  cmd->add_option("--checkpoint", a->options.checkpoint, "best, last, or a checkpoint file")->capture_default_str();
  cmd->add_option("--split", a->options.split,
                  "split or subset to evaluate (default eval.split, then data.test_split)");
  cmd->add_option("--horizon", a->options.horizon, "rollout frames (0 = whole sequences; default eval.horizon)")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--out", a->options.out_dir, "output folder (default <run.output>/eval-<split>)");
  cmd->add_option("--sequence", a->options.sequences, "evaluate only this sequence id (repeatable)");
  cmd->add_flag("--quiet", a->quiet, "no progress line");
  return [a]() {
    LoadedConfig loaded = load_config(a->config);
    train::check_selection(loaded.typed);
    a->options.progress = !a->quiet;
    const std::unique_ptr<dist::Group> group = join_group(loaded.typed);
    a->options.group = group.get();
    const train::EvalReport r = train::run_evaluation(loaded.typed, load_plugins().registry, a->options);
    if (group && !group->is_root()) return static_cast<int>(kOk);
    std::printf("%s on %s: %lld sequences, %lld frames, %lld diverged, %.2f ms per frame\n", r.model.c_str(),
                r.split.c_str(), static_cast<long long>(r.sequences), static_cast<long long>(r.frames),
                static_cast<long long>(r.diverged), r.ms_per_frame);
    const std::string chosen = r.chosen_on == "none" ? "chosen by nothing" : "chosen on " + r.chosen_on;
    std::printf("checkpoint: %s, %s, evaluated on %s%s\n", r.checkpoint_kind.c_str(), chosen.c_str(), r.split.c_str(),
                data::run_layout::chosen_on_names(r.chosen_on, r.split)
                    ? " (the same split: optimistic figures, marked in reports)"
                    : "");
    // One column per registered metric (docs/metrics.md); the ground
    // truth's own values below, for the metrics measured on it.
    std::printf("%-14s", "");
    for (const metrics::MetricDef& d : metrics::registered())
      std::printf(" %*s", d.unit == metrics::Unit::Millimetre ? 16 : 12, d.key.c_str());
    std::printf("\n");
    print_row("overall", r.overall);
    for (const auto& [type, m] : r.per_type) print_row(type, m);
    train::MetricSummary truth = r.truth;
    for (const metrics::MetricDef& d : metrics::registered()) truth.try_emplace(d.key);  // "-" where not measured
    print_row("ground truth", truth);
    for (const metrics::MetricDef& d : metrics::registered())
      std::printf("%s: %s\n", d.key.c_str(), d.description.c_str());
    std::printf("written: %s/%s, %s%s%s\n", r.out_dir.c_str(), data::run_layout::kMetrics, data::run_layout::kSequences,
                loaded.typed.eval.save_predictions ? ", " : "",
                loaded.typed.eval.save_predictions ? data::run_layout::kPredictions : "");
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
