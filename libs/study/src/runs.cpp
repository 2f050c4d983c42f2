// Resolving a study's experiments into runs (see runs.h).
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
  for (const StudyExperiment& e : study.experiments) {
    StudyRun r;
    r.name = e.name;
    r.dir = (fs::path(study.output) / e.name).string();
    cfg::Node tree = cfg::load_file(e.file);
    for (const std::string& s : study.set) cfg::apply_set(tree, s);
    for (const std::string& s : e.set) cfg::apply_set(tree, s);
    set_string(tree, "run", "output", r.dir);
    set_string(tree, "data", "dataset", study.dataset.folder);
    r.config = train::read_experiment(tree, e.file);
    // Selection never sees the test split: the best checkpoint (and any
    // epoch or variant chosen from the validation curve) comes from
    // data.val_split, and training reads data.train_split.
    const train::DataConfig& d = r.config.data;
    for (const auto& [field, split] :
         {std::pair<const char*, const std::string*>{"data.val_split", &d.val_split},
          std::pair<const char*, const std::string*>{"data.train_split", &d.train_split}}) {
      if (*split == d.test_split) {
        throw InputError(e.file, field,
                         "a split other than data.test_split (selection and training never read the test split)",
                         *split);
      }
    }
    r.config_yaml = cfg::to_yaml(cfg::to_node(r.config)) + "\n";
    for (const std::string& s : e.steps.empty() ? study.steps : e.steps)
      if (s != "report" && !(s == "train" && !e.checkpoint.empty())) r.steps.push_back(s);
    r.eval_splits = study.eval.splits;
    if (r.eval_splits.empty())
      r.eval_splits.push_back(!r.config.eval.split.empty() ? r.config.eval.split : r.config.data.test_split);
    const std::string file = data::run_layout::checkpoint(study.eval.checkpoint);
    r.external_checkpoint = !e.checkpoint.empty();
    r.checkpoint = !r.external_checkpoint ? (fs::path(r.dir) / file).string()
                   : fs::is_directory(e.checkpoint) || fs::path(e.checkpoint).extension() != ".pt"
                       ? (fs::path(e.checkpoint) / file).string()
                       : e.checkpoint;
    runs.push_back(std::move(r));
  }
  return runs;
}

}  // namespace layers::study
