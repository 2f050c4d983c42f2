// Resolving a study's experiments into runs, one per seed (see runs.h).
#include "layers/study/runs.h"

#include <filesystem>

#include "layers/core/error.h"
#include "layers/data/run_layout.h"

namespace fs = std::filesystem;

namespace layers::study {
namespace {

// Sets tree[a][b] to a string scalar (a path must not go through YAML parsing).
void set_string(cfg::Node& tree, const char* section, const char* key, const std::string& value) {
  cfg::Node& s = tree.child(section);
  if (s.kind != cfg::Node::Kind::Map) {
    s = cfg::Node{};
    s.kind = cfg::Node::Kind::Map;
  }
  cfg::Node& v = s.child(key);
  v = cfg::Node{};
  v.kind = cfg::Node::Kind::Scalar;
  v.scalar = value;
}

}  // namespace

std::vector<StudyRun> resolve_runs(const StudyConfig& study) {
  std::vector<StudyRun> runs;
  for (std::size_t i = 0; i < study.experiments.size(); ++i) {
    const StudyExperiment& e = study.experiments[i];
    cfg::Node base = cfg::load_file(e.file);
    for (const std::string& s : study.set) cfg::apply_set(base, s);
    for (const std::string& s : e.set) cfg::apply_set(base, s);
    set_string(base, "data", "dataset", study.dataset.folder);
    const int seeds = e.seeds > 0 ? e.seeds : study.seeds;
    const std::uint64_t first_seed = train::read_experiment(base, e.file).run.seed;
    const bool checkpoint_file =
        !e.checkpoint.empty() && !fs::is_directory(e.checkpoint) && fs::path(e.checkpoint).extension() == ".pt";
    if (seeds > 1 && checkpoint_file)
      throw InputError(study.source, "experiments[" + std::to_string(i) + "].seeds",
                       "1 with a checkpoint file (a run folder lends each seed its seed-<s>/ checkpoint)",
                       std::to_string(seeds));
    for (int k = 0; k < seeds; ++k) {
      StudyRun r;
      r.experiment = e.name;
      r.repeated = seeds > 1;
      r.seed = first_seed + static_cast<std::uint64_t>(k);
      const std::string seed_folder = data::run_layout::seed_folder(r.seed);
      r.name = r.repeated ? e.name + "/" + seed_folder : e.name;
      r.dir = (r.repeated ? fs::path(study.output) / e.name / seed_folder : fs::path(study.output) / e.name).string();
      cfg::Node tree = base;
      set_string(tree, "run", "output", r.dir);
      if (r.repeated) set_string(tree, "run", "seed", std::to_string(r.seed));
      r.config = train::read_experiment(tree, e.file);
      // Selection never sees the test split (refused before anything runs).
      train::check_selection(r.config);
      r.config_yaml = cfg::to_yaml(cfg::to_node(r.config)) + "\n";
      for (const std::string& s : e.steps.empty() ? study.steps : e.steps)
        if (s != "report" && !(s == "train" && !e.checkpoint.empty())) r.steps.push_back(s);
      r.eval_splits = study.eval.splits;
      if (r.eval_splits.empty()) r.eval_splits.push_back(train::evaluated_split(r.config));
      const std::string file = data::run_layout::checkpoint(study.eval.checkpoint);
      r.external_checkpoint = !e.checkpoint.empty();
      const fs::path lent = r.repeated ? fs::path(e.checkpoint) / seed_folder : fs::path(e.checkpoint);
      r.checkpoint = !r.external_checkpoint ? (fs::path(r.dir) / file).string()
                     : checkpoint_file      ? e.checkpoint
                                            : (lent / file).string();
      runs.push_back(std::move(r));
    }
  }
  return runs;
}

}  // namespace layers::study
