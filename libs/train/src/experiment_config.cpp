// Reading an experiment file (see experiment_config.h).
#include "layers/train/experiment_config.h"

#include <utility>

#include "layers/core/error.h"

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

std::string evaluated_split(const ExperimentConfig& config, const std::string& requested) {
  if (!requested.empty()) return requested;
  return !config.eval.split.empty() ? config.eval.split : config.data.test_split;
}

void check_selection(const ExperimentConfig& config) {
  const DataConfig& d = config.data;
  for (const auto& [field, split] : {std::pair<const char*, const std::string*>{"data.val_split", &d.val_split},
                                     std::pair<const char*, const std::string*>{"data.train_split", &d.train_split}}) {
    if (*split == d.test_split)
      throw InputError(config.source, field,
                       "a split other than data.test_split '" + d.test_split +
                           "' (training and the choice of the best checkpoint never read the test split)",
                       "'" + *split + "'");
  }
}

}  // namespace layers::train
