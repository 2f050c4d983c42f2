// layers/core/log.h -- logging setup on top of spdlog.
//
// Libraries log through spdlog's default logger (spdlog::info, ...). The
// CLI sets the level once from --log-level; messages go to stderr so that
// stdout stays machine-readable.
#pragma once

#include <string>

namespace layers {

// Accepts trace, debug, info, warn, error, critical, off. Throws InputError
// naming the flag otherwise.
void set_log_level(const std::string& level, const std::string& source = "--log-level");

}  // namespace layers
