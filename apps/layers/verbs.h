// apps/layers/verbs.h -- how the CLI's verbs plug into main.cpp.
//
// Each verb file defines a `register_<verb>` function that adds its CLI11
// subcommand and returns the function to run when it is chosen. Verbs
// report failures by throwing (InputError -> exit 1, UsageError -> exit 2)
// or by returning a non-zero exit code.
#pragma once

#include <CLI/CLI.hpp>

#include <functional>
#include <string>
#include <vector>

namespace layers::app {

// Options every verb shares (set on the top-level command).
struct Global {
  std::string log_level = "info";
};

using VerbRun = std::function<int()>;

VerbRun register_config(CLI::App& app, const Global& global);
VerbRun register_export(CLI::App& app, const Global& global);
VerbRun register_body(CLI::App& app, const Global& global);
VerbRun register_generate(CLI::App& app, const Global& global);
VerbRun register_models(CLI::App& app, const Global& global);
VerbRun register_info(CLI::App& app, const Global& global);
VerbRun register_stats(CLI::App& app, const Global& global);
VerbRun register_validate(CLI::App& app, const Global& global);
VerbRun register_crosscheck(CLI::App& app, const Global& global);
VerbRun register_train(CLI::App& app, const Global& global);
VerbRun register_eval(CLI::App& app, const Global& global);
VerbRun register_rollout(CLI::App& app, const Global& global);
VerbRun register_bench(CLI::App& app, const Global& global);
VerbRun register_report(CLI::App& app, const Global& global);
VerbRun register_run(CLI::App& app, const Global& global);
VerbRun register_launch(CLI::App& app, const Global& global);
VerbRun register_tpose(CLI::App& app, const Global& global);
VerbRun register_animate(CLI::App& app, const Global& global);

// Exit codes of the CLI (README "Exit codes").
enum Exit : int { kOk = 0, kFailure = 1, kUsage = 2 };

}  // namespace layers::app
