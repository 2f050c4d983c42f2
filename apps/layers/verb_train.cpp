// `layers train <experiment.yaml>`: train the experiment's model (see
// libs/train/include/layers/train/trainer.h).
#include <cstdio>

#include "config_loading.h"
#include "layers/core/atomic_file.h"
#include "layers/train/trainer.h"
#include "plugins.h"
#include "verbs.h"

#include <filesystem>

namespace layers::app {

VerbRun register_train(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("train", "Train the model of an experiment config (configs/experiments/*.yaml)");
  struct Args {
    ConfigArgs config;
    bool resume = false, quiet = false;
  };
  auto a = std::make_shared<Args>();
  add_config_options(*cmd, a->config, /*required=*/true);
  cmd->add_flag("--resume", a->resume, "continue from <run.output>/checkpoint-last.pt if it exists");
  cmd->add_flag("--quiet", a->quiet, "no progress line");
  return [a]() {
    LoadedConfig loaded = load_config(a->config);
    std::filesystem::create_directories(loaded.typed.run.output);
    write_text_atomic((std::filesystem::path(loaded.typed.run.output) / "experiment.yaml").string(),
                      cfg::to_yaml(loaded.resolved));
    train::TrainOptions options;
    options.resume = a->resume;
    options.progress = !a->quiet;
    const train::TrainReport r = train::run_training(loaded.typed, load_plugins().registry, options);
    std::printf("trained %d epochs (%lld steps), %lld trainable parameters\n", r.epochs_done,
                static_cast<long long>(r.steps), static_cast<long long>(r.trainable_parameters));
    for (const auto& e : r.epochs)
      std::printf("  epoch %d: loss %.5g  val error %.2f mm  %.1f frames/s  %.1f s\n", e.epoch, e.loss,
                  e.val_error_mm, e.frames_per_second, e.seconds);
    std::printf("checkpoints: %s, %s\n", r.last_checkpoint.c_str(), r.best_checkpoint.c_str());
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
