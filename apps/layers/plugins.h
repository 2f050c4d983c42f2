// apps/layers/plugins.h -- loading the model plugins once for the verbs
// that need them; refused plugins are logged as warnings.
#pragma once

#include "layers/zoo/plugin_loader.h"
#include "layers/zoo/registry.h"

namespace layers::app {

struct Plugins {
  zoo::Registry registry;
  zoo::LoadReport report;
};

// Loads every plugin on the search path (LAYERS_PLUGIN_PATH, plugins/ next
// to the binary, the binary's folder).
Plugins& load_plugins();

}  // namespace layers::app
