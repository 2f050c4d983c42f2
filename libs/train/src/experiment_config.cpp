// Reading an experiment file (see experiment_config.h).
#include "layers/train/experiment_config.h"

namespace layers::train {

ExperimentConfig read_experiment(const cfg::Node& tree, const std::string& source) {
  ExperimentConfig config = cfg::read<ExperimentConfig>(tree);
  config.source = source;
  return config;
}

ExperimentConfig load_experiment(const std::string& path, const std::vector<std::string>& sets) {
  cfg::Node tree = cfg::load_file(path);
  for (const std::string& s : sets) cfg::apply_set(tree, s);
  return read_experiment(tree, path);
}

}  // namespace layers::train
