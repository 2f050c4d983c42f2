// Which rows the picture and the viewer show (see shown_rows.h).
#include "shown_rows.h"

#include <algorithm>
#include <filesystem>

#include "layers/core/error.h"

namespace layers::report {
namespace {

namespace fs = std::filesystem;

std::shared_ptr<data::Dataset> open_dataset(const std::string& path) {
  return std::make_shared<data::Dataset>(data::Dataset::open(path));
}

// The ground-truth dataset: the option, else a run's data.dataset as
// written or relative to the run folder and its parents.
std::shared_ptr<data::Dataset> ground_truth(const std::vector<RunResults>& runs, const PictureOptions& options,
                                            const std::string& sequence, const std::string& what,
                                            std::vector<std::string>& notes) {
  std::vector<std::string> candidates;
  if (!options.dataset.empty()) {
    candidates.push_back(options.dataset);
  } else {
    for (const RunResults& r : runs) {
      if (r.dataset.empty()) continue;
      candidates.push_back(r.dataset);
      if (fs::path(r.dataset).is_relative())
        for (fs::path dir = fs::absolute(r.dir).lexically_normal(); dir.has_relative_path(); dir = dir.parent_path())
          candidates.push_back((dir / r.dataset).string());
    }
  }
  std::string why = "no run names its dataset (experiment.yaml data.dataset)";
  for (const std::string& c : candidates) {
    if (!fs::exists(c)) {
      why = "dataset " + c + " not found";
      continue;
    }
    try {
      auto ds = open_dataset(c);
      if (ds->contains(sequence)) return ds;
      why = "dataset " + c + " has no sequence " + sequence;
    } catch (const std::exception& e) {
      why = e.what();
    }
  }
  notes.push_back(what + ": no ground-truth row (" + why + "; pass --dataset)");
  return nullptr;
}

}  // namespace

ShownRows shown_rows(const std::vector<RunResults>& runs, const PictureOptions& options, const std::string& what,
                     std::vector<std::string>& notes) {
  std::vector<ShownRow> predicted;
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    if (r.eval->predictions.empty()) {
      notes.push_back(what + ": " + r.name + " has no predictions.h5 (eval.save_predictions off?)");
      continue;
    }
    try {
      predicted.push_back({r.name, open_dataset(r.eval->predictions)});
    } catch (const std::exception& e) {
      notes.push_back(what + ": " + r.name + ": cannot read its predictions: " + e.what());
    }
  }
  if (predicted.empty()) throw Error("no run has readable predictions (eval-<split>/predictions.h5)");
  ShownRows shown;
  shown.sequence = options.sequence;
  if (shown.sequence.empty()) {
    for (const std::string& id : predicted.front().source->ids()) {
      if (std::all_of(predicted.begin(), predicted.end(), [&](const ShownRow& r) { return r.source->contains(id); })) {
        shown.sequence = id;
        break;
      }
    }
    if (shown.sequence.empty()) shown.sequence = predicted.front().source->ids().front();
  }
  shown.n_frames = -1;
  for (const ShownRow& r : predicted) {
    if (!r.source->contains(shown.sequence)) {
      notes.push_back(what + ": " + r.label + " has no prediction of " + shown.sequence);
      continue;
    }
    const std::int64_t n = r.source->info(shown.sequence).n_frames;
    shown.n_frames = shown.n_frames < 0 ? n : std::min(shown.n_frames, n);
    shown.rows.push_back(r);
  }
  if (shown.rows.empty()) throw Error("no run has a prediction of sequence '" + shown.sequence + "'");
  if (auto truth = ground_truth(runs, options, shown.sequence, what, notes)) {
    shown.n_frames = std::min(shown.n_frames, truth->info(shown.sequence).n_frames);
    shown.rows.insert(shown.rows.begin(), ShownRow{"ground truth", truth});
    shown.has_truth = true;
  }
  return shown;
}

}  // namespace layers::report
