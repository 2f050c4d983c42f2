// Reading and checking study files (see config.h).
#include "layers/study/config.h"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>

#include "layers/core/error.h"
#include "lists.h"

namespace fs = std::filesystem;

namespace layers::study {
namespace {

const std::vector<std::string> kStudySteps{"train", "eval", "bench", "report"};
const std::vector<std::string> kRunSteps{"train", "eval", "bench"};

// `file` relative to the folder of `base` (unchanged when absolute or empty).
std::string beside(const std::string& base, const std::string& file) {
  if (file.empty() || fs::path(file).is_absolute()) return file;
  return (fs::path(base).parent_path() / file).lexically_normal().string();
}

void check_steps(const std::string& source, const std::string& key, const std::vector<std::string>& steps,
                 const std::vector<std::string>& allowed) {
  for (std::size_t i = 0; i < steps.size(); ++i)
    if (!contains(allowed, steps[i]))
      throw InputError(source, key + "[" + std::to_string(i) + "]", "one of " + join(allowed), "'" + steps[i] + "'");
}

bool valid_run_name(const std::string& name) {
  if (name.empty() || name == "." || name == ".." || name == "report") return false;
  return std::all_of(name.begin(), name.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '+' || c == '.';
  });
}

}  // namespace

train::BenchOptions study_bench() {
  train::BenchOptions b;
  b.levels = 1;
  b.min_time = 0.3;
  b.train = true;
  b.far_body = false;
  return b;
}

StudyConfig load_study(const std::string& path, const std::vector<std::string>& sets) {
  cfg::Node tree = cfg::load_file(path);
  for (const std::string& s : sets) cfg::apply_set(tree, s);
  StudyConfig study = cfg::read<StudyConfig>(tree);
  study.source = path;
  if (study.name.empty()) study.name = fs::path(path).stem().string();
  if (study.output.empty()) study.output = "runs/" + study.name;
  if (study.dataset.config.empty()) {
    if (!study.dataset.set.empty())
      throw InputError(path, "dataset.set", "no generator overrides without dataset.config",
                       std::to_string(study.dataset.set.size()) + " override(s)");
  } else {
    study.dataset.config = beside(path, study.dataset.config);
    if (!fs::is_regular_file(study.dataset.config))
      throw InputError(path, "dataset.config", "a generator config file (relative to the study file)",
                       "'" + study.dataset.config + "' (no such file)");
  }
  for (std::string& r : study.requires_) {
    r = beside(path, r);
    if (!fs::is_regular_file(r))
      throw InputError(path, "requires", "study files (relative to this one)", "'" + r + "' (no such file)");
  }
  check_steps(path, "steps", study.steps, kStudySteps);
  if (study.experiments.empty()) throw InputError(path, "experiments", "at least one experiment", "none");
  std::set<std::string> names;
  for (std::size_t i = 0; i < study.experiments.size(); ++i) {
    StudyExperiment& e = study.experiments[i];
    const std::string key = "experiments[" + std::to_string(i) + "]";
    if (!valid_run_name(e.name))
      throw InputError(path, key + ".name", "a folder name of letters, digits, _ - + . (not 'report')",
                       "'" + e.name + "'");
    if (!names.insert(e.name).second)
      throw InputError(path, key + ".name", "a name used once", "'" + e.name + "' again");
    e.file = beside(path, e.file);
    if (!fs::is_regular_file(e.file))
      throw InputError(path, key + ".file", "an experiment config (relative to the study file)",
                       "'" + e.file + "' (no such file)");
    check_steps(path, key + ".steps", e.steps, kRunSteps);
  }
  for (const auto& [row, partner] : study.report.partners) {
    if (row == partner)
      throw InputError(path, "report.partners." + row, "another experiment to compare it with", "'" + partner + "'");
    for (const std::string& name : {row, partner})
      if (names.count(name) == 0)
        throw InputError(path, "report.partners." + row, "experiment names of this study", "'" + name + "'");
  }
  return study;
}

}  // namespace layers::study
