// `layers config`: load a YAML config (an experiment, a generator config or
// a study) with its includes and --set overrides, check it against its
// typed sections, and print (or save) the resolved config.
#include <fstream>
#include <iostream>

#include "config_loading.h"
#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/generate/generator_config.h"
#include "layers/study/config.h"
#include "layers/zoo/model_config.h"
#include "output_folder.h"
#include "plugins.h"
#include "verbs.h"

namespace layers::app {

namespace {

// What a config file is, by its top-level keys: a study lists experiments,
// a generator config describes scenes, anything else is an experiment.
enum class ConfigKind { Experiment, Generator, Study };

ConfigKind kind_of(const cfg::Node& tree) {
  if (tree.find("experiments")) return ConfigKind::Study;
  for (const char* key : {"sequences", "frames", "drape_frames", "garments", "wind", "sim", "body"})
    if (tree.find(key)) return ConfigKind::Generator;
  return ConfigKind::Experiment;
}

}  // namespace

VerbRun register_config(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("config",
                                 "Check a config file -- an experiment, a generator config (configs/data) or a study "
                                 "(configs/studies) -- and print it resolved (includes and --set applied)");
  struct Args {
    ConfigArgs config;
    std::string out;
  };
  auto args = std::make_shared<Args>();
  add_config_options(*cmd, args->config, /*required=*/true);
  cmd->add_option("--out", args->out, "also write the resolved config to this file");
  return [args]() {
    if (!args->out.empty()) claim_new_output(args->out, "--out", {args->config.file});
    cfg::Node tree = cfg::load_file(args->config.file);
    for (const auto& s : args->config.sets) cfg::apply_set(tree, s);
    std::string text;
    switch (kind_of(tree)) {
      case ConfigKind::Study: {
        const study::StudyConfig study = study::load_study(args->config.file, args->config.sets);
        text = cfg::to_yaml(cfg::to_node(study));
        break;
      }
      case ConfigKind::Generator: {
        // As the generator resolves it (motion folders expanded, garment files read).
        const auto config = generate::load_generator_config(args->config.file, args->config.sets, false);
        text = cfg::to_yaml(cfg::to_node(config));
        break;
      }
      case ConfigKind::Experiment: {
        LoadedConfig loaded = load_config(args->config);
        // An experiment names its model; the model is checked by creating
        // it: its name must be registered and the plugin must accept its
        // parameters.
        if (loaded.typed.model.kind == cfg::Node::Kind::Null)
          throw InputError(args->config.file, "model",
                           "an experiment with a model section (or a generator config, or a study)", "none");
        zoo::create_model(load_plugins().registry, loaded.typed.model);
        text = cfg::to_yaml(loaded.resolved);
        break;
      }
    }
    std::cout << text;
    if (!args->out.empty()) write_text_atomic(args->out, text);
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
