// layers/data/run_layout.h -- the file names of a run folder
// (<run.output>: what `layers train/eval/bench` write and `layers report`
// reads) and of a study folder (`layers run`). Every writer and reader
// names these files through here, as dataset_files.h does for a dataset.
//
//   <run>/experiment.yaml            the resolved experiment
//   <run>/checkpoint-{last,best}.pt  training
//   <run>/selection.json             training: what chose checkpoint-best.pt
//   <run>/eval-<split>/metrics.json, sequences.csv, predictions.h5
//   <run>/bench.json                 `layers bench`
//   <run>/steps.yaml                 `layers run`'s records (also <study>/steps.yaml)
//   <study>/report/report.md         the study's report
//   <study>/<name>/seed-<s>/         one repetition of a study experiment
//                                    repeated over seeds (run.seed = s)
#pragma once

#include <algorithm>
#include <cstdint>
#include <string>

namespace layers::data::run_layout {

inline constexpr const char* kExperiment = "experiment.yaml";
inline constexpr const char* kBench = "bench.json";
inline constexpr const char* kSteps = "steps.yaml";
inline constexpr const char* kSelection = "selection.json";    // written with the checkpoints
inline constexpr const char* kMetrics = "metrics.json";        // in eval-<split>/
inline constexpr const char* kSequences = "sequences.csv";     // in eval-<split>/
inline constexpr const char* kPredictions = "predictions.h5";  // in eval-<split>/ (eval.save_predictions)
inline constexpr const char* kReportFolder = "report";         // in a study folder
inline constexpr const char* kReport = "report.md";            // in the report folder

// "checkpoint-<which>.pt"; which is last or best.
std::string checkpoint(const std::string& which);
// "eval-<split>".
std::string eval_folder(const std::string& split);
// Whether a file or folder name is an eval-<split> folder.
bool is_eval_folder(const std::string& name);
// "seed-<seed>": the run folder of one repetition of a study experiment.
std::string seed_folder(std::uint64_t seed);
// Whether a folder name is seed-<digits>; `seed` (optional) gets the number.
bool is_seed_folder(const std::string& name, std::uint64_t* seed = nullptr);
// Whether a name in a run folder shows a run was made there: a checkpoint,
// bench.json or an eval-<split> folder.
bool is_result(const std::string& name);

// A selection record's `chosen_on` (selection.json, checkpoints,
// metrics.json): the names of the splits whose sequences the validation
// read, joined by '+' ("val"; "val+test" when a sequence of both was
// read), "none" or "" when nothing was chosen. True when it names `split`.
inline bool chosen_on_names(const std::string& chosen_on, const std::string& split) {
  std::size_t start = 0;
  while (start <= chosen_on.size()) {
    const std::size_t end = std::min(chosen_on.find('+', start), chosen_on.size());
    if (chosen_on.compare(start, end - start, split) == 0 && end - start == split.size()) return true;
    start = end + 1;
  }
  return false;
}

}  // namespace layers::data::run_layout
