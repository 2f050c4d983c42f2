// tests/regression/regression_paths.h -- where the regression tests find
// their committed inputs (the fixture dataset, goldens, tolerances), the
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
// The committed dataset the model goldens run on (docs/studies.md): a
// folder `fixture/` packed with tar + xz by make_fixture.sh.
inline std::string fixture_archive() { return regression_dir() + "/fixture.tar.xz"; }
inline std::string golden_file(const std::string& run) { return regression_dir() + "/goldens/" + run + ".json"; }
inline std::string tolerances_file() { return regression_dir() + "/tolerances.yaml"; }

// LAYERS_UPDATE_GOLDENS set and not "0".
inline bool updating_goldens() {
  const char* v = std::getenv("LAYERS_UPDATE_GOLDENS");
  return v && *v && std::string(v) != "0";
}

// Unpacks the fixture into <parent>/fixture (kept when already there);
// returns that folder, or "" after printing why it failed.
inline std::string unpack_fixture(const std::string& parent) {
  const std::string dir = parent + "/fixture";
  if (test::run_command("test -f '" + dir + "/dataset.yaml'").exit_code == 0) return dir;
  const test::CommandResult r =
      test::run_command("mkdir -p '" + parent + "' && tar -xJf '" + fixture_archive() + "' -C '" + parent + "'");
  if (r.exit_code != 0) {
    std::fprintf(stderr, "cannot unpack %s: %s\n", fixture_archive().c_str(), r.output.c_str());
    return "";
  }
  return dir;
}

// Hex sha256 of a file (coreutils' sha256sum), or "unreadable".
inline std::string sha256_of(const std::string& path) {
  const test::CommandResult r = test::run_command("sha256sum '" + path + "'");
  if (r.exit_code != 0 || r.output.size() < 64) return "unreadable";
  return r.output.substr(0, 64);
}

}  // namespace layers::regression
