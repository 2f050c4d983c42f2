// apps/layers/main.cpp -- entry point of the `layers` CLI: global flags,
// verb dispatch and the mapping of errors to exit codes
// (0 ok, 1 failure or bad input, 2 bad usage).
#include <spdlog/spdlog.h>

#include <algorithm>
#include <cstdlib>
#include <iostream>
#include <iterator>
#include <map>

#include "layers/core/error.h"
#include "layers/core/log.h"
#include "layers/core/memory.h"
#include "layers/core/source_revision.h"
#include "verbs.h"

int main(int argc, char** argv) {
  // OpenMP threads that wait for work sleep instead of spinning: torch's
  // parallel regions are short, and spinning threads steal the cores of a
  // shared machine (measured: most of a training run spent spin-waiting
  // on a busy 2-core host). Set before torch starts OpenMP; a user's own
  // setting wins.
  setenv("OMP_WAIT_POLICY", "PASSIVE", /*overwrite=*/0);
  // Freed tensors stay with the process for the next step's (memory.h).
  layers::keep_freed_memory();
  using namespace layers;
  CLI::App app{
      "layers: generate multi-layered garment datasets, train and compare learned garment "
      "simulators.\nExit codes: 0 success, 1 failure (bad input, failed validation), 2 bad usage."};
  app.require_subcommand(1);
  app::Global global;
  app.add_option("--log-level", global.log_level, "trace, debug, info, warn, error, critical or off")
      ->capture_default_str();
  app.set_version_flag("--version", std::string("layers ") + source_revision(),
                       "Print the source revision this build was made from and exit");

  std::map<CLI::App*, app::VerbRun> verbs;
  auto add = [&](app::VerbRun (*reg)(CLI::App&, const app::Global&)) {
    std::size_t before = app.get_subcommands({}).size();
    app::VerbRun run = reg(app, global);
    auto subs = app.get_subcommands({});
    if (subs.size() != before + 1) throw Error("verb registration must add exactly one subcommand");
    verbs[subs.back()] = std::move(run);
  };

  try {
    add(app::register_generate);
    add(app::register_body);
    add(app::register_info);
    add(app::register_validate);
    add(app::register_crosscheck);
    add(app::register_stats);
    add(app::register_export);
    add(app::register_tpose);
    add(app::register_animate);
    add(app::register_models);
    add(app::register_train);
    add(app::register_eval);
    add(app::register_rollout);
    add(app::register_bench);
    add(app::register_report);
    add(app::register_run);
    add(app::register_launch);
    add(app::register_config);
  } catch (const std::exception& e) {
    std::cerr << "layers: internal error: " << e.what() << "\n";
    return app::kFailure;
  }

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    if (e.get_exit_code() == 0) return app.exit(e);  // --help, --version
    // One line, like every other error (CLI11 adds a second, "Run with --help ...").
    std::string where = "layers";
    for (const CLI::App* sub = &app; !sub->get_subcommands().empty();) {
      sub = sub->get_subcommands().front();
      where += " " + sub->get_name();
    }
    std::cerr << "layers: " << e.what() << " (see " << where << " --help)\n";
    return app::kUsage;
  }

  try {
    // Checked after parsing, so that --help still wins over a bad value.
    static const char* const kLevels[] = {"trace", "debug", "info", "warn", "error", "critical", "off"};
    if (std::find(std::begin(kLevels), std::end(kLevels), global.log_level) == std::end(kLevels))
      throw UsageError("--log-level: expected one of trace, debug, info, warn, error, critical, off, got '" +
                       global.log_level + "'");
    set_log_level(global.log_level);
    for (auto* sub : app.get_subcommands()) return verbs.at(sub)();
  } catch (const UsageError& e) {
    std::cerr << "layers: " << e.what() << "\n";
    return app::kUsage;
  } catch (const std::exception& e) {
    std::cerr << "layers: error: " << e.what() << "\n";
    return app::kFailure;
  }
  return app::kOk;
}
