// Plugin loading for the CLI (see plugins.h).
#include "plugins.h"

#include <spdlog/spdlog.h>

namespace layers::app {

Plugins& load_plugins() {
  static Plugins plugins;
  static bool loaded = false;
  if (!loaded) {
    loaded = true;
    plugins.report = zoo::load_all(plugins.registry);
    for (const auto& p : plugins.report.problems) spdlog::warn("plugin refused: {}", p.message);
    for (const auto& p : plugins.report.shadowed) spdlog::debug("plugin shadowed: {}", p.message);
    for (const auto& p : plugins.report.passed_over) spdlog::warn("plugin passed over: {}", p.message);
  }
  return plugins;
}

}  // namespace layers::app
