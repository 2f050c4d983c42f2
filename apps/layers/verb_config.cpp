// `layers config`: load a YAML config with its includes and --set
// overrides, check it against the typed sections, and print (or save) the
// resolved config.
#include <fstream>
#include <iostream>

#include "config_loading.h"
#include "layers/core/atomic_file.h"
#include "layers/zoo/model_config.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_config(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("config", "Check a config file and print it resolved (includes and --set applied)");
  struct Args {
    ConfigArgs config;
    std::string out;
  };
  auto args = std::make_shared<Args>();
  add_config_options(*cmd, args->config, /*required=*/true);
  cmd->add_option("--out", args->out, "also write the resolved config to this file");
  return [args]() {
    LoadedConfig loaded = load_config(args->config);
    // A model section is checked by creating the model: its name must be
    // registered and the plugin must accept its parameters.
    if (loaded.typed.model.kind != cfg::Node::Kind::Null) zoo::create_model(load_plugins().registry, loaded.typed.model);
    std::string text = cfg::to_yaml(loaded.resolved);
    std::cout << text;
    if (!args->out.empty()) write_text_atomic(args->out, text);
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
