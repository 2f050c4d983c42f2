// `layers models`: the registered models, the plugin each came from, the
// search path, and the plugins that were refused.
#include <cstdio>

#include "layers/zoo/plugin_loader.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_models(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("models", "List registered models and where their plugins were found");
  auto strict = std::make_shared<bool>(false);
  cmd->add_flag("--strict", *strict, "exit 1 if any plugin was refused");
  return [strict]() {
    Plugins& plugins = load_plugins();
    std::printf("zoo API v%d; plugin search path:\n", zoo::api_version());
    for (const auto& dir : plugins.report.searched) std::printf("  %s\n", dir.c_str());
    auto entries = plugins.registry.entries();
    std::printf("%zu model%s registered:\n", entries.size(), entries.size() == 1 ? "" : "s");
    for (const auto& e : entries)
      std::printf("  %-24s %s\n  %-24s   from %s\n", e.name.c_str(), e.description.c_str(), "", e.plugin_path.c_str());
    if (!plugins.report.problems.empty()) {
      std::printf("%zu plugin%s refused:\n", plugins.report.problems.size(),
                  plugins.report.problems.size() == 1 ? "" : "s");
      for (const auto& p : plugins.report.problems) std::printf("  %s\n", p.message.c_str());
    }
    return (*strict && !plugins.report.problems.empty()) ? static_cast<int>(kFailure) : static_cast<int>(kOk);
  };
}

}  // namespace layers::app
