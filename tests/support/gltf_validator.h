// tests/support/gltf_validator.h -- npm's Khronos gltf-validator on a file,
// for tests built with layers_test_uses_browser_tools: a reason to skip
// where node or the validator is missing, else its report's counts.
#pragma once

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "run_command.h"

namespace layers::test {

// "" when the validator can run here, else why not (for GTEST_SKIP).
inline std::string gltf_validator_missing() {
  const std::string node = LAYERS_TEST_NODE, tools = LAYERS_TEST_BROWSER_DIR;
  if (node.empty()) return "node not found when CMake ran";
  if (!std::filesystem::exists(tools + "/node_modules/gltf-validator"))
    return "gltf-validator not installed in " + tools + " (scripts/setup.sh runs npm ci there)";
  return "";
}

// The validator's report of `path` (errors, warnings, infos, hints and
// the messages), and its raw output for failure messages.
struct GltfReport {
  int exit_code = -1;
  nlohmann::json counts;
  std::string output;
  bool clean() const {
    return exit_code == 0 && counts["errors"] == 0 && counts["warnings"] == 0 && counts["infos"] == 0 &&
           counts["hints"] == 0;
  }
};

inline GltfReport validate_gltf(const std::string& path) {
  const CommandResult r =
      run_command(std::string(LAYERS_TEST_NODE) + " " + LAYERS_TEST_BROWSER_DIR + "/gltf_validate.js " + path);
  GltfReport report{r.exit_code, nullptr, r.output};
  if (r.exit_code == 0) report.counts = nlohmann::json::parse(r.output);
  return report;
}

}  // namespace layers::test
