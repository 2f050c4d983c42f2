// Logging setup: stderr sink and level parsing (see log.h).
#include "layers/core/log.h"

#include <spdlog/sinks/stdout_color_sinks.h>
#include <spdlog/spdlog.h>

#include "layers/core/error.h"

namespace layers {

void set_log_level(const std::string& level, const std::string& source) {
  static const char* names[] = {"trace", "debug", "info", "warn", "error", "critical", "off"};
  for (int i = 0; i < 7; ++i) {
    if (level == names[i]) {
      static bool installed = false;
      if (!installed) {
        auto logger = spdlog::stderr_color_mt("layers");
        logger->set_pattern("[%H:%M:%S.%e] [%^%l%$] %v");
        spdlog::set_default_logger(logger);
        installed = true;
      }
      spdlog::set_level(static_cast<spdlog::level::level_enum>(i));
      return;
    }
  }
  throw InputError(source, "", "one of trace, debug, info, warn, error, critical, off", "'" + level + "'");
}

}  // namespace layers
