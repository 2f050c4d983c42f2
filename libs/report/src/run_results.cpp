// Reading run folders back: metrics.json, bench.json, experiment.yaml
// (see run_results.h).
#include "layers/report/run_results.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "layers/core/config_node.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/data/run_layout.h"
#include "layers/metrics/registry.h"

namespace layers::report {

namespace run_layout = data::run_layout;
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// Typed access to JSON fields with errors naming the file and key path.
class Reader {
 public:
  explicit Reader(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }

  json parse(const std::string& text) const {
    try {
      return json::parse(text);
    } catch (const json::parse_error& e) {
      throw InputError(file_, "", "valid JSON", e.what());
    }
  }
  const json& object(const json& parent, const std::string& key, const std::string& path) const {
    const json& v = required(parent, key, path);
    if (!v.is_object()) throw InputError(file_, path, "an object", v.type_name());
    return v;
  }
  const json& array(const json& parent, const std::string& key, const std::string& path) const {
    const json& v = required(parent, key, path);
    if (!v.is_array()) throw InputError(file_, path, "an array", v.type_name());
    return v;
  }
  const json& required(const json& parent, const std::string& key, const std::string& path) const {
    if (!parent.is_object() || !parent.contains(key)) throw InputError(file_, path, "a value", "nothing");
    return parent.at(key);
  }
  // Missing or null: NaN.
  double number(const json& parent, const std::string& key, const std::string& path) const {
    if (!parent.is_object() || !parent.contains(key) || parent.at(key).is_null()) return kAbsent;
    const json& v = parent.at(key);
    if (!v.is_number()) throw InputError(file_, path, "a number or null", v.type_name());
    return v.get<double>();
  }
  // Missing or null: `fallback`.
  std::int64_t integer(const json& parent, const std::string& key, const std::string& path,
                       std::int64_t fallback = 0) const {
    if (!parent.is_object() || !parent.contains(key) || parent.at(key).is_null()) return fallback;
    const json& v = parent.at(key);
    if (!v.is_number()) throw InputError(file_, path, "an integer or null", v.type_name());
    return v.get<std::int64_t>();
  }
  std::string text(const json& parent, const std::string& key, const std::string& path) const {
    if (!parent.is_object() || !parent.contains(key) || parent.at(key).is_null()) return "";
    const json& v = parent.at(key);
    if (!v.is_string()) throw InputError(file_, path, "a string", v.type_name());
    return v.get<std::string>();
  }
  // {mean, std, count}; count 0 means no value (the evaluator writes 0s then).
  Stat stat(const json& parent, const std::string& key, const std::string& path, bool required_field) const {
    Stat s;
    if (!required_field && (!parent.is_object() || !parent.contains(key) || parent.at(key).is_null())) return s;
    const json& v = object(parent, key, path);
    s.mean = number(v, "mean", path + ".mean");
    s.std = number(v, "std", path + ".std");
    s.count = integer(v, "count", path + ".count", std::isfinite(s.mean) ? 1 : 0);
    if (s.count == 0) s.mean = s.std = kAbsent;
    return s;
  }
  // Every registered metric the object has; error_mm required when asked.
  MetricStats metrics(const json& parent, const std::string& key, const std::string& path, bool require_error) const {
    const json& v = object(parent, key, path);
    MetricStats out;
    for (const metrics::MetricDef& d : metrics::registered()) {
      const bool required_field = require_error && d.key == metrics::kError;
      if (required_field || (v.contains(d.key) && !v.at(d.key).is_null()))
        out.by_key[d.key] = stat(v, d.key, path + "." + d.key, required_field);
    }
    return out;
  }

 private:
  std::string file_;
};

EvalResults parse_metrics_json(const Reader& r, const json& doc, const std::string& file) {
  EvalResults e;
  e.file = file;
  if (!doc.is_object()) throw InputError(file, "", "a JSON object", doc.type_name());
  e.model = r.text(doc, "model", "model");
  if (e.model.empty()) throw InputError(file, "model", "the model's name", "nothing");
  e.split = r.text(doc, "split", "split");
  e.dataset = r.text(doc, "dataset", "dataset");
  e.checkpoint = r.text(doc, "checkpoint", "checkpoint");
  e.sequences = r.integer(doc, "sequences", "sequences");
  e.frames = r.integer(doc, "frames", "frames");
  e.diverged = r.integer(doc, "diverged", "diverged");
  e.parameters = r.integer(doc, "parameters", "parameters");
  e.horizon = r.integer(doc, "horizon", "horizon");
  e.ms_per_frame = r.number(doc, "ms_per_frame", "ms_per_frame");
  e.diverge_mm = r.number(doc, "diverge_mm", "diverge_mm");
  e.overall = r.metrics(doc, "overall", "overall", /*require_error=*/true);
  if (doc.contains("truth") && !doc.at("truth").is_null()) {
    const json& t = r.object(doc, "truth", "truth");
    for (const metrics::MetricDef& d : metrics::registered())
      if (d.truth && t.contains(d.key)) e.truth[d.key] = r.number(t, d.key, "truth." + d.key);
  }
  if (doc.contains("per_type") && !doc.at("per_type").is_null()) {
    const json& types = r.object(doc, "per_type", "per_type");
    for (const auto& [type, value] : types.items())
      e.per_type.emplace_back(type, r.metrics(types, type, "per_type." + type, false));
  }
  if (doc.contains("by_step") && !doc.at("by_step").is_null()) {
    const json& steps = r.array(doc, "by_step", "by_step");
    for (std::size_t i = 0; i < steps.size(); ++i) {
      const std::string p = "by_step[" + std::to_string(i) + "]";
      StepMetrics s;
      s.step = r.integer(steps[i], "step", p + ".step", static_cast<std::int64_t>(i + 1));
      for (const metrics::MetricDef& d : metrics::registered())
        if (steps[i].contains(d.key)) s.by_key[d.key] = r.number(steps[i], d.key, p + "." + d.key);
      s.sequences = r.integer(steps[i], "sequences", p + ".sequences");
      e.by_step.push_back(s);
    }
  }
  e.selection.evaluated_on = e.split;
  if (doc.contains("selection") && !doc.at("selection").is_null()) {
    const json& sel = r.object(doc, "selection", "selection");
    auto text_or = [&](const char* key, const std::string& fallback) {
      const std::string v = r.text(sel, key, std::string("selection.") + key);
      return v.empty() ? fallback : v;
    };
    e.selection.checkpoint = text_or("checkpoint", "unknown");
    e.selection.chosen_on = text_or("chosen_on", "unknown");
    e.selection.evaluated_on = text_or("evaluated_on", e.split);
    e.selection.chosen_epoch = r.integer(sel, "chosen_epoch", "selection.chosen_epoch");
    e.selection.epochs = r.integer(sel, "epochs", "selection.epochs");
    e.selection.metric = r.text(sel, "metric", "selection.metric");
  }
  if (doc.contains("per_sequence") && !doc.at("per_sequence").is_null()) {
    const json& seqs = r.array(doc, "per_sequence", "per_sequence");
    for (std::size_t i = 0; i < seqs.size(); ++i) {
      const std::string p = "per_sequence[" + std::to_string(i) + "]";
      SequenceMetrics s;
      s.id = r.text(seqs[i], "id", p + ".id");
      s.error_mm = r.number(seqs[i], metrics::kError, p + "." + metrics::kError);
      s.diverged_at = r.integer(seqs[i], "diverged_at", p + ".diverged_at", -1);
      s.diverge_reason = r.text(seqs[i], "diverge_reason", p + ".diverge_reason");
      e.per_sequence.push_back(s);
    }
  }
  return e;
}

// data.dataset, model.name and data.test_split of a resolved
// experiment.yaml ("" when absent).
struct ExperimentFacts {
  std::string dataset, model, test_split;
  std::string windows_per_epoch;  // train.windows_per_epoch ("" when not set)
  std::string settings;           // the experiment without run.seed, run.output and data.dataset (YAML)
};
ExperimentFacts experiment_facts(const std::string& file) {
  const cfg::Node root = cfg::load_file(file);
  cfg::Node settings = root;
  if (cfg::Node* run = settings.find("run")) run->erase("seed"), run->erase("output");
  if (cfg::Node* data = settings.find("data")) data->erase("dataset");
  auto scalar = [&](const char* section, const char* key) -> std::string {
    const cfg::Node* s = root.find(section);
    const cfg::Node* v = s ? s->find(key) : nullptr;
    return v && v->kind == cfg::Node::Kind::Scalar ? v->scalar : "";
  };
  return {scalar("data", "dataset"), scalar("model", "name"), scalar("data", "test_split"),
          scalar("train", "windows_per_epoch"), cfg::to_yaml(settings)};
}

// selection.json's validation error per epoch against the windows seen by
// the end of each epoch: its windows_by_epoch, else the experiment's
// windows_per_epoch times the epoch; NaN where neither is known. Without
// the per-epoch record, the chosen epoch's error alone (only_best).
LearningCurve learning_curve(const Reader& reader, const json& doc, double windows_per_epoch) {
  LearningCurve c;
  c.split = reader.text(doc, "val_split", "val_split");
  c.horizon = reader.integer(doc, "val_horizon", "val_horizon");
  c.sequences = reader.integer(doc, "val_sequences", "val_sequences", -1);
  std::vector<double> vals;
  if (doc.contains("val_error_mm_by_epoch")) {
    for (const json& v : reader.array(doc, "val_error_mm_by_epoch", "val_error_mm_by_epoch"))
      vals.push_back(v.is_number() && v.get<double>() >= 0 ? v.get<double>() : kAbsent);  // -1: none that epoch
  } else {
    const std::int64_t chosen = reader.integer(doc, "chosen_epoch", "chosen_epoch");
    const std::int64_t done = reader.integer(doc, "epochs_done", "epochs_done");
    const double best = reader.number(doc, "best_val_error_mm", "best_val_error_mm");
    if (chosen > 0 && std::isfinite(best)) {
      if (chosen > done)
        throw InputError(reader.file(), "chosen_epoch", "an epoch from 1 to epochs_done (" + std::to_string(done) + ")",
                         std::to_string(chosen));
      vals.assign(static_cast<std::size_t>(done), kAbsent);
      vals[static_cast<std::size_t>(chosen - 1)] = best;
      c.only_best = true;
    }
  }
  const json* windows = doc.contains("windows_by_epoch") ? &doc.at("windows_by_epoch") : nullptr;
  double seen = 0;
  for (std::size_t k = 0; k < vals.size(); ++k) {
    c.val_error_mm.push_back(vals[k]);
    double w = kAbsent;
    if (windows && windows->is_array() && k < windows->size() && (*windows)[k].is_number())
      w = (*windows)[k].get<double>();
    else if (windows_per_epoch > 0)
      w = windows_per_epoch;
    seen += w;
    c.windows_seen.push_back(seen);
  }
  // One epoch's count unknown: no x axis for the curve (the table still
  // lists its errors), rather than a curve that stops there.
  if (!std::isfinite(seen)) c.windows_seen.assign(c.windows_seen.size(), kAbsent);
  return c;
}

// The seed-<s> folders directly in `dir`, in seed order.
std::vector<std::pair<std::uint64_t, std::string>> seed_folders_in(const fs::path& dir) {
  std::vector<std::pair<std::uint64_t, std::string>> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    std::uint64_t seed = 0;
    if (entry.is_directory() && run_layout::is_seed_folder(entry.path().filename().string(), &seed))
      found.emplace_back(seed, entry.path().string());
  }
  std::sort(found.begin(), found.end());
  return found;
}

// eval-<split> folder of a run ("" when none).
std::string eval_folder(const fs::path& dir, const std::string& split) {
  if (!split.empty()) return (dir / run_layout::eval_folder(split)).string();
  if (fs::is_directory(dir / run_layout::eval_folder("test"))) return (dir / run_layout::eval_folder("test")).string();
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec))
    if (entry.is_directory() && run_layout::is_eval_folder(entry.path().filename().string()))
      found.push_back(entry.path().string());
  std::sort(found.begin(), found.end());
  return found.empty() ? "" : found.front();
}

}  // namespace

Stat MetricStats::get(const std::string& key) const {
  const auto it = by_key.find(key);
  return it == by_key.end() ? Stat{} : it->second;
}

double StepMetrics::get(const std::string& key) const {
  const auto it = by_key.find(key);
  return it == by_key.end() ? kAbsent : it->second;
}

double EvalResults::truth_of(const std::string& key) const {
  const auto it = truth.find(key);
  return it == truth.end() ? kAbsent : it->second;
}

std::int64_t EvalResults::first_divergence_step() const {
  std::int64_t first = -1;
  for (const SequenceMetrics& s : per_sequence)
    if (s.diverged_at >= 0 && (first < 0 || s.diverged_at - 1 < first)) first = s.diverged_at - 1;
  return first;
}

std::string evaluated_sequences(const std::vector<RunResults>& runs) {
  std::vector<std::size_t> all(runs.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
  return evaluated_sequences(runs, all);
}

std::string evaluated_sequences(const std::vector<RunResults>& runs, const std::vector<std::size_t>& plotted) {
  std::vector<std::string> splits;
  for (std::size_t i : plotted) {
    const RunResults& r = runs.at(i);
    if (r.eval && !r.eval->split.empty() && std::find(splits.begin(), splits.end(), r.eval->split) == splits.end())
      splits.push_back(r.eval->split);
  }
  if (splits.empty()) return "the evaluated sequences";
  if (splits.size() == 1) return "the " + splits.front() + " sequences";
  std::string joined;
  for (std::size_t i = 0; i < splits.size(); ++i)
    joined += (i == 0 ? "" : i + 1 == splits.size() ? " or " : ", ") + splits[i];
  return "each run's evaluated sequences (" + joined + ")";
}

std::string selection_flag(const RunResults& run) {
  if (!run.eval) return "";
  const SelectionRecord& s = run.eval->selection;
  if (run_layout::chosen_on_names(s.chosen_on, run.test_split))
    return "checkpoint chosen on the test split '" + s.chosen_on + "'";
  if (run_layout::chosen_on_names(s.chosen_on, s.evaluated_on))
    return "checkpoint chosen on '" + s.chosen_on + "', the split it is evaluated on (optimistic figures)";
  return "";
}

std::vector<std::string> expand_seed_folders(const std::vector<std::string>& dirs) {
  std::vector<std::string> out;
  for (const std::string& dir : dirs) {
    const fs::path path(dir);
    std::error_code ec;
    bool own = fs::exists(path / run_layout::kExperiment);
    for (const auto& entry : fs::directory_iterator(path, ec))
      own = own || run_layout::is_result(entry.path().filename().string());
    const std::vector<std::pair<std::uint64_t, std::string>> seeds = seed_folders_in(path);
    if (own || seeds.empty()) {
      out.push_back(dir);
      continue;
    }
    for (const auto& [seed, folder] : seeds) out.push_back(folder);
  }
  return out;
}

EvalResults parse_metrics(const std::string& json_text, const std::string& file) {
  const Reader r(file);
  return parse_metrics_json(r, r.parse(json_text), file);
}

BenchResults parse_bench(const std::string& json_text, const std::string& file) {
  const Reader r(file);
  const json doc = r.parse(json_text);
  if (!doc.is_object()) throw InputError(file, "", "a JSON object", doc.type_name());
  BenchResults b;
  b.file = file;
  b.model = r.text(doc, "model", "model");
  if (b.model.empty()) throw InputError(file, "model", "the model's name", "nothing");
  b.sequence = r.text(doc, "sequence", "sequence");
  b.parameters = r.integer(doc, "parameters", "parameters");
  b.threads = static_cast<int>(r.integer(doc, "threads", "threads"));
  const json& rows = r.array(doc, "rows", "rows");
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const std::string p = "rows[" + std::to_string(i) + "]";
    BenchPoint row;
    row.level = static_cast<int>(r.integer(rows[i], "level", p + ".level"));
    if (rows[i].contains("far_body")) {
      const json& far = rows[i].at("far_body");
      if (!far.is_boolean()) throw InputError(file, p + ".far_body", "true or false", far.type_name());
      row.far_body = far.get<bool>();
    }
    row.garment_vertices = r.integer(rows[i], "garment_vertices", p + ".garment_vertices");
    row.body_vertices = r.integer(rows[i], "body_vertices", p + ".body_vertices");
    row.ms_per_frame = r.number(rows[i], "ms_per_frame", p + ".ms_per_frame");
    row.train_ms_per_frame = r.number(rows[i], "train_ms_per_frame", p + ".train_ms_per_frame");
    if (rows[i].contains("counters") && rows[i].at("counters").is_object())
      for (const auto& [k, v] : rows[i].at("counters").items())
        row.counters[k] = r.number(rows[i].at("counters"), k, p + ".counters." + k);
    b.rows.push_back(row);
  }
  return b;
}

RunResults load_run(const std::string& dir, const std::string& split) {
  RunResults run;
  run.dir = dir;
  fs::path path(dir);
  const fs::path folder = path.has_filename() ? path : path.parent_path();
  run.name = folder.filename().string();
  if (run.name.empty() || run.name == ".") run.name = fs::absolute(path).lexically_normal().filename().string();
  run.experiment = run.name;
  if (run_layout::is_seed_folder(run.name, &run.seed)) {
    // <name>/seed-<s>: one seed of the experiment <name>.
    const std::string parent = fs::absolute(folder).lexically_normal().parent_path().filename().string();
    run.repeated = !parent.empty();
    if (run.repeated) {
      run.experiment = parent;
      run.name = parent + "/" + run.name;
    }
  }
  if (!fs::is_directory(path)) {
    run.problems.push_back("no such run folder");
    return run;
  }
  const fs::path experiment = path / run_layout::kExperiment;
  double windows_per_epoch = 0;  // the experiment's train.windows_per_epoch (0: every window, count unknown)
  if (fs::exists(experiment)) {
    try {
      const ExperimentFacts facts = experiment_facts(experiment.string());
      run.dataset = facts.dataset, run.model = facts.model;
      if (!facts.test_split.empty()) run.test_split = facts.test_split;
      run.settings = facts.settings;
      if (!facts.windows_per_epoch.empty()) windows_per_epoch = std::stod(facts.windows_per_epoch);
    } catch (const std::exception& e) {
      run.problems.push_back(std::string("cannot read the experiment: ") + e.what());
    }
  }
  const std::string eval_dir = eval_folder(path, split);
  const fs::path metrics = eval_dir.empty() ? fs::path() : fs::path(eval_dir) / run_layout::kMetrics;
  if (eval_dir.empty() || !fs::exists(metrics)) {
    run.problems.push_back(
        "no evaluation (" +
        (eval_dir.empty() ? std::string("no eval-<split>/metrics.json") : metrics.string() + " is missing") +
        "): run `layers eval <experiment.yaml>` for this run first");
  } else {
    try {
      run.eval = parse_metrics(read_text_file(metrics.string()), metrics.string());
      if (fs::exists(fs::path(eval_dir) / run_layout::kPredictions))
        run.eval->predictions = (fs::path(eval_dir) / run_layout::kPredictions).string();
      run.model = run.eval->model;
      if (run.dataset.empty()) run.dataset = run.eval->dataset;
    } catch (const std::exception& e) {
      run.problems.push_back(std::string("cannot read the evaluation: ") + e.what());
    }
  }
  const fs::path selection = path / run_layout::kSelection;
  if (fs::exists(selection)) {
    try {
      const Reader reader(selection.string());
      const json doc = reader.parse(read_text_file(selection.string()));
      if (run.eval && run.eval->selection.checkpoint == "best")
        run.eval->selection.val_error_mm = reader.number(doc, "best_val_error_mm", "best_val_error_mm");
      run.curve = learning_curve(reader, doc, windows_per_epoch);
    } catch (const std::exception& e) {
      run.problems.push_back(std::string("cannot read the selection record: ") + e.what());
    }
  }
  // The evaluation on the validation split besides the one read (a
  // reference row's value on the learning curves' measure).
  const std::string val_split = run.curve.split.empty() ? std::string("val") : run.curve.split;
  const fs::path val_metrics = path / run_layout::eval_folder(val_split) / run_layout::kMetrics;
  if ((!run.eval || run.eval->split != val_split) && fs::exists(val_metrics)) {
    try {
      run.val_eval = parse_metrics(read_text_file(val_metrics.string()), val_metrics.string());
    } catch (const std::exception& e) {
      run.problems.push_back(std::string("cannot read the validation evaluation: ") + e.what());
    }
  }
  const fs::path bench = path / run_layout::kBench;
  if (!fs::exists(bench)) {
    run.problems.push_back("no bench.json (run `layers bench <experiment.yaml>` for speed by scene size)");
  } else {
    try {
      run.bench = parse_bench(read_text_file(bench.string()), bench.string());
      if (run.model.empty()) run.model = run.bench->model;
    } catch (const std::exception& e) {
      run.problems.push_back(std::string("cannot read the benchmark: ") + e.what());
    }
  }
  return run;
}

std::vector<ReferenceLevel> curve_references(const std::vector<RunResults>& runs, std::vector<std::string>* notes) {
  const auto note = [&](const std::string& text) {
    if (notes) notes->push_back(text);
  };
  const LearningCurve* protocol = nullptr;
  bool curves = false;
  for (const RunResults& r : runs) curves = curves || !r.curve.val_error_mm.empty();
  if (!curves) return {};
  for (const RunResults& r : runs) {
    if (r.curve.val_error_mm.empty() || r.curve.horizon <= 0) continue;
    if (protocol && (protocol->split != r.curve.split || protocol->horizon != r.curve.horizon ||
                     protocol->sequences != r.curve.sequences)) {
      note("learning curves: no reference levels, the curves were validated on different protocols");
      return {};
    }
    protocol = &r.curve;
  }
  std::vector<ReferenceLevel> out;
  for (const RunResults& r : runs) {
    const EvalResults* e = nullptr;
    for (const std::optional<EvalResults>* candidate : {&r.eval, &r.val_eval})
      if (*candidate && (*candidate)->parameters == 0 && (!protocol || (*candidate)->split == protocol->split))
        e = &**candidate;
    if (e == nullptr) continue;
    if (protocol == nullptr) {
      note("learning curves: " + r.name +
           " is not drawn as a reference level: no curve records its validation protocol (selection.json "
           "val_horizon)");
      continue;
    }
    const bool frames = e->horizon == protocol->horizon;
    const bool sequences = protocol->sequences == 0 || protocol->sequences >= e->sequences;
    if (!frames || !sequences) {
      note("learning curves: " + r.name + " is not drawn as a reference level: evaluated on " +
           std::to_string(e->sequences) + " " + e->split + " sequences over " + std::to_string(e->horizon) +
           " frames, the curves on " +
           (protocol->sequences == 0 ? std::string("all") : "the first " + std::to_string(protocol->sequences)) + " " +
           protocol->split + " sequence" + (protocol->sequences == 0 || protocol->sequences > 1 ? "s" : "") + " over " +
           std::to_string(protocol->horizon) + " frames");
      continue;
    }
    out.push_back({r.name, e->overall.get(metrics::kError).mean});
  }
  return out;
}

}  // namespace layers::report
