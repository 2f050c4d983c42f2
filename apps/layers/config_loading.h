// apps/layers/config_loading.h -- the config options every config-driven
// verb shares (<file> plus repeated --set key=value), read as an
// experiment (layers/train/experiment_config.h).
#pragma once

#include <CLI/CLI.hpp>

#include <string>
#include <vector>

#include "layers/core/config.h"
#include "layers/core/run_config.h"
#include "layers/train/experiment_config.h"

namespace layers::app {

struct ConfigArgs {
  std::string file;
  std::vector<std::string> sets;
};

// Top level of a config file: an experiment (layers/train).
using TopConfig = train::ExperimentConfig;

struct LoadedConfig {
  TopConfig typed;
  cfg::Node resolved;  // typed sections written back with defaults filled in
};

void add_config_options(CLI::App& cmd, ConfigArgs& args, bool required);
LoadedConfig load_config(const ConfigArgs& args);

}  // namespace layers::app
