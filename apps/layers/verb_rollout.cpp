// `layers rollout <experiment.yaml> --sequence ID`: one autoregressive
// rollout of the trained model, saved as LAYERS-H5 with its metrics and
// optionally exported to OBJ/PC2 (the evaluator restricted to chosen
// sequences, plus export).
#include <cstdio>
#include <filesystem>

#include "config_loading.h"
#include "layers/data/dataset.h"
#include "layers/data/export.h"
#include "layers/data/run_layout.h"
#include "layers/metrics/registry.h"
#include "layers/train/evaluator.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_rollout(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("rollout", "Roll a trained model out on one or more sequences and save the result");
  struct Args {
    ConfigArgs config;
    train::EvalOptions options;
    std::string format;
  };
  auto a = std::make_shared<Args>();
  a->options.horizon = 0;
  add_config_options(*cmd, a->config, /*required=*/true);
  cmd->add_option("--sequence", a->options.sequences, "sequence id (repeatable)")->required();
  cmd->add_option("--frames", a->options.horizon, "predicted frames (0 = to the end of the sequence)")
      ->capture_default_str();
  cmd->add_option("--checkpoint", a->options.checkpoint, "best, last, or a checkpoint file")->capture_default_str();
  cmd->add_option("--out", a->options.out_dir, "output folder")->required();
  cmd->add_option("--export", a->format, "also export predictions and body: obj or pc2");
  return [a]() {
    LoadedConfig loaded = load_config(a->config);
    loaded.typed.eval.save_predictions = true;
    a->options.progress = false;
    const train::EvalReport r = train::run_evaluation(loaded.typed, load_plugins().registry, a->options);
    std::printf("%s: %lld frames predicted, error %s mm, %lld diverged\n", r.model.c_str(),
                static_cast<long long>(r.frames), metrics::format(r.overall.at(metrics::kError)).c_str(),
                static_cast<long long>(r.diverged));
    const std::string predictions = (std::filesystem::path(r.out_dir) / data::run_layout::kPredictions).string();
    std::printf("written: %s, %s/%s\n", predictions.c_str(), r.out_dir.c_str(), data::run_layout::kMetrics);
    if (!a->format.empty()) {
      const data::ExportFormat format = data::parse_export_format(a->format, "--export");
      const data::Dataset predicted = data::Dataset::open(predictions);
      const std::string dir = (std::filesystem::path(r.out_dir) / a->format).string();
      std::size_t files = 0;
      for (const std::string& id : a->options.sequences)
        files += data::export_sequence(predicted, id, format, 0, -1, dir).size();
      std::printf("exported %zu files to %s\n", files, dir.c_str());
    }
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
