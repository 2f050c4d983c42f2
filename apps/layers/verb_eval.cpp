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
#include "layers/train/evaluator.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {
namespace {

std::string percent(const zoo::MeanStd& m) {
  if (m.count == 0) return "-";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.2f%%", 100.0 * m.mean);
  return buf;
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
                r.chosen_on == r.split ? " (the same split: optimistic figures, marked in reports)" : "");
    // L-collision twice (docs/metrics.md): the paper's plain nearest-vertex
    // rule, comparable with its figures, and ours with the open-edge rule.
    const char* row = "%-14s %22s %10s %13s %12s %10s %10s\n";
    std::printf(row, "", "error (mm)", "H-coll", "L-coll paper", "L-coll ours", "H-cross", "L-cross");
    std::printf(row, "overall", zoo::format(r.overall.error_mm).c_str(), percent(r.overall.h_collision).c_str(),
                percent(r.overall.l_collision_plain).c_str(), percent(r.overall.l_collision).c_str(),
                percent(r.overall.h_crossing).c_str(), percent(r.overall.l_crossing).c_str());
    for (const auto& [type, m] : r.per_type)
      std::printf(row, type.c_str(), zoo::format(m.error_mm).c_str(), percent(m.h_collision).c_str(),
                  percent(m.l_collision_plain).c_str(), percent(m.l_collision).c_str(), percent(m.h_crossing).c_str(),
                  percent(m.l_crossing).c_str());
    const auto pct = [](double v) { return std::isfinite(v) ? 100.0 * v : 0.0; };
    std::printf(
        "ground truth: H-coll %.2f%%, L-coll paper %.2f%%, L-coll ours %.2f%%, H-cross %.2f%%, L-cross %.2f%%\n",
        pct(r.truth_h_collision), pct(r.truth_l_collision_plain), pct(r.truth_l_collision), pct(r.truth_h_crossing),
        pct(r.truth_l_crossing));
    std::printf(
        "L-coll paper: behind the normal plane of the nearest inner vertex (LayersNet's rule); L-coll ours: the "
        "same, except beside an open edge (hem, cuff) of the inner garment (docs/metrics.md)\n");
    std::printf("written: %s/%s, %s%s%s\n", r.out_dir.c_str(), data::run_layout::kMetrics, data::run_layout::kSequences,
                loaded.typed.eval.save_predictions ? ", " : "",
                loaded.typed.eval.save_predictions ? data::run_layout::kPredictions : "");
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
