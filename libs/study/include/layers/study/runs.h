// layers/study/runs.h -- the experiments of a study resolved into runs:
// each experiment file with the study's and its own overrides, run.output
// = <output>/<name>, data.dataset = the study's dataset folder, its steps,
// splits and the checkpoint its eval and bench use. An experiment repeated
// over seeds is one run per seed, <output>/<name>/seed-<s> (config.h).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/study/config.h"
#include "layers/train/experiment_config.h"

namespace layers::study {

// One experiment of a study, resolved.
struct StudyRun {
  std::string name, dir;   // dir = <output>/<name>; repeated: name <name>/seed-<s>, dir <output>/<name>/seed-<s>
  std::string experiment;  // the experiment's name in the study file
  std::uint64_t seed = 0;  // run.seed
  bool repeated = false;   // one of several seeds
  train::ExperimentConfig config;  // with run.output = dir, data.dataset = the study's folder
  std::string config_yaml;         // the resolved experiment (saved as <dir>/experiment.yaml)
  std::vector<std::string> steps;  // train, eval, bench (report is the study's)
  std::vector<std::string> eval_splits;
  std::string checkpoint;            // the checkpoint file eval and bench use
  bool external_checkpoint = false;  // from StudyExperiment::checkpoint (no train step)
};

// Reads every experiment of the study (InputError for a bad file or set).
std::vector<StudyRun> resolve_runs(const StudyConfig& study);

}  // namespace layers::study
