// Loading of config files for the CLI (see config_loading.h).
#include "config_loading.h"

#include "layers/core/error.h"

namespace layers::app {

void add_config_options(CLI::App& cmd, ConfigArgs& args, bool required) {
  auto* file = cmd.add_option("config", args.file, "YAML config file");
  if (required) file->required();
  file->check(CLI::ExistingFile);
  cmd.add_option("--set", args.sets, "override a value: --set key.path=value (repeatable)");
}

LoadedConfig load_config(const ConfigArgs& args) {
  cfg::Node tree = cfg::load_file(args.file);
  for (const auto& s : args.sets) cfg::apply_set(tree, s);
  LoadedConfig out;
  out.typed = train::read_experiment(tree, args.file);
  out.resolved = cfg::to_node(out.typed);
  return out;
}

}  // namespace layers::app
