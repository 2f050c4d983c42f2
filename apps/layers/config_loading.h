// apps/layers/config_loading.h -- the config options every config-driven
// verb shares (<file> plus repeated --set key=value) and the typed
// top-level sections known so far.
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "layers/core/config.h"
#include "layers/core/run_config.h"

namespace layers::app {

struct ConfigArgs {
  std::string file;
  std::vector<std::string> sets;
};

// Top level of a config file. Sections not known yet to this build are
// rejected as unknown keys.
struct TopConfig {
  RunConfig run;
  cfg::Node model;  // checked by the model zoo (name + the plugin's own parameters)
  cfg::Node data;   // dataset section

  template <class V>
  void visit(V& v) {
    v("run", run);
    v("model", model);
    v("data", data);
  }
};

struct LoadedConfig {
  TopConfig typed;
  cfg::Node resolved;  // typed sections written back with defaults filled in
};

void add_config_options(CLI::App& cmd, ConfigArgs& args, bool required);
LoadedConfig load_config(const ConfigArgs& args);

}  // namespace layers::app
