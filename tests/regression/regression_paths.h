// tests/regression/regression_paths.h -- where the regression tests find
// their committed inputs (generator settings, goldens, tolerances), the
// switch that rewrites goldens on purpose, and the sha256 they print so
// that two machines can compare the data they used.
#pragma once

#include <cstdio>
#include <cstdlib>
#include <string>

#include "run_command.h"
#include "test_paths.h"

namespace layers::regression {

inline std::string regression_dir() { return test::source_dir() + "/tests/regression"; }
// The generator settings of the generator's regression (tiny's scenes).
inline std::string generator_config() { return regression_dir() + "/generator.yaml"; }
inline std::string golden_file(const std::string& run) { return regression_dir() + "/goldens/" + run + ".json"; }
inline std::string tolerances_file() { return regression_dir() + "/tolerances.yaml"; }

// LAYERS_UPDATE_GOLDENS set and not "0".
inline bool updating_goldens() {
  const char* v = std::getenv("LAYERS_UPDATE_GOLDENS");
  return v && *v && std::string(v) != "0";
}

// Hex sha256 of a file (coreutils' sha256sum), or "unreadable".
inline std::string sha256_of(const std::string& path) {
  const test::CommandResult r = test::run_command("sha256sum '" + path + "'");
  if (r.exit_code != 0 || r.output.size() < 64) return "unreadable";
  return r.output.substr(0, 64);
}

}  // namespace layers::regression
