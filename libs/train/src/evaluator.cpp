// Evaluation of a trained model on a split (see evaluator.h).
#include "layers/train/evaluator.h"

#include <spdlog/spdlog.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <map>
#include <optional>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/progress.h"
#include "layers/data/run_layout.h"
#include "layers/data/shard_writer.h"
#include "layers/dist/group.h"
#include "layers/metrics/registry.h"
#include "layers/train/checkpoint.h"
#include "layers/train/session.h"
#include "layers/train/trainer.h"
#include "layers/train/window_loader.h"

namespace layers::train {
namespace {

using json = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json to_json(const metrics::MeanStd& m) {
  return {{"mean", number(m.mean)}, {"std", number(m.std)}, {"count", m.count}};
}

// Every metric's summary, in the order of `defs`.
json to_json(const MetricSummary& s, const std::vector<metrics::MetricDef>& defs) {
  json out = json::object();
  for (const metrics::MetricDef& d : defs) out[d.key] = to_json(s.at(d.key));
  return out;
}

// Per registered metric (registry order), the values of sequences (or of
// garments) gathered for a summary.
using Columns = std::vector<std::vector<double>>;

MetricSummary summary_of(const Columns& columns, const std::vector<metrics::MetricDef>& defs) {
  MetricSummary out;
  for (std::size_t k = 0; k < defs.size(); ++k) out[defs[k].key] = metrics::finite_mean_std(columns[k]);
  return out;
}

// The rollout as a LAYERS-H5 sequence: ground-truth body and wind of the
// rolled-out frames, garments = ground truth at frames 0 and 1, then the predictions.
data::SequenceData prediction_sequence(const data::Dataset& dataset, const SequenceRollout& r,
                                       const GarmentSelection& selection) {
  const data::SequenceInfo& info = dataset.info(r.id);
  auto statics = dataset.statics(r.id);
  const std::int64_t n = r.frames.frames();
  data::Window w = dataset.read_frames(r.id, 0, n);
  data::SequenceData seq;
  seq.id = r.id;
  seq.n_frames = n;
  seq.motion = info.motion;
  seq.seed = info.seed;
  seq.tags = info.tags;
  seq.shape = info.shape;
  static_cast<data::BodyStatic&>(seq.body) = statics->body;
  static_cast<data::BodyFrames&>(seq.body) = std::move(w.body);
  seq.wind = std::move(w.wind);
  const std::vector<std::size_t> picked = selection.pick(statics->garments);
  for (std::size_t j = 0; j < picked.size(); ++j) {
    data::GarmentData g;
    static_cast<data::GarmentStatic&>(g) = statics->garments[picked[j]];
    const at::Tensor all = at::cat({r.frames.garments[j].slice(0, 0, 2), r.result.predictions[j]}).contiguous();
    g.positions.assign(all.data_ptr<float>(), all.data_ptr<float>() + all.numel());
    seq.garments.push_back(std::move(g));
  }
  return seq;
}

std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  std::ostringstream out;
  out.precision(6);
  out << v;
  return out.str();
}

// ---- error growth rate (stability studies, docs/studies.md) ----------------
// Least-squares slope of a rollout's per-frame error (mm per frame) over
// the frames before it diverged; NaN with fewer than two such frames.
double error_growth_mm_per_frame(const std::vector<FrameMetrics>& frames) {
  double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (const FrameMetrics& m : frames) {
    const double error = m.error_mm();
    if (m.diverged || !std::isfinite(error)) break;
    const double x = static_cast<double>(m.frame);
    n += 1, sx += x, sy += error, sxx += x * x, sxy += x * error;
  }
  const double den = n * sxx - sx * sx;
  return n >= 2 && den > 0 ? (n * sxy - sx * sy) / den : kNaN;
}

// ---- a rollout's result as bytes (from the rank that made it to rank 0) --
// Exact: doubles and floats travel as their bytes, so rank 0 sums the same
// values one process would.
class Bytes {
 public:
  std::string data;
  template <class T>
  void put(const T& v) {
    data.append(reinterpret_cast<const char*>(&v), sizeof v);
  }
  void put(const std::vector<double>& v) {
    put<std::uint64_t>(v.size());
    data.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  }
  void put(const std::string& v) {
    put<std::uint64_t>(v.size());
    data += v;
  }
};

class Unbytes {
 public:
  explicit Unbytes(const std::string& d) : data_(d) {}
  template <class T>
  T get() {
    T v;
    take(&v, sizeof v);
    return v;
  }
  std::vector<double> doubles() {
    std::vector<double> v(get<std::uint64_t>());
    take(v.data(), v.size() * sizeof(double));
    return v;
  }
  std::string text() {
    std::string v(get<std::uint64_t>(), '\0');
    take(v.data(), v.size());
    return v;
  }
  void take(void* out, std::size_t n) {
    if (pos_ + n > data_.size()) throw Error("evaluation: a rank's rollout result is truncated");
    std::memcpy(out, data_.data() + pos_, n);
    pos_ += n;
  }

 private:
  const std::string& data_;
  std::size_t pos_ = 0;
};

std::string encode(const RolloutResult& r) {
  Bytes b;
  b.put<std::uint64_t>(r.frames.size());
  for (const FrameMetrics& m : r.frames) {
    b.put(m.frame), b.put<std::uint8_t>(m.diverged), b.put(m.truth);
    b.put<std::uint64_t>(m.value.size());
    for (const metrics::FrameValue& v : m.value) b.put(v.scene), b.put(v.garments);
  }
  b.put(r.diverged_at), b.put(r.diverge_reason), b.put(r.model_seconds);
  b.put<std::uint64_t>(r.predictions.size());
  for (const at::Tensor& p : r.predictions) {
    const at::Tensor c = p.detach().to(at::kCPU, at::kFloat).contiguous();
    b.put<std::uint64_t>(c.dim());
    for (std::int64_t d = 0; d < c.dim(); ++d) b.put<std::int64_t>(c.size(d));
    b.data.append(reinterpret_cast<const char*>(c.data_ptr<float>()), c.numel() * sizeof(float));
  }
  return b.data;
}

RolloutResult decode(const std::string& bytes) {
  Unbytes u(bytes);
  RolloutResult r;
  r.frames.resize(u.get<std::uint64_t>());
  for (FrameMetrics& m : r.frames) {
    m.frame = u.get<std::int64_t>(), m.diverged = u.get<std::uint8_t>() != 0, m.truth = u.doubles();
    m.value.resize(u.get<std::uint64_t>());
    for (metrics::FrameValue& v : m.value) v.scene = u.get<double>(), v.garments = u.doubles();
  }
  r.diverged_at = u.get<std::int64_t>(), r.diverge_reason = u.text(), r.model_seconds = u.get<double>();
  r.predictions.resize(u.get<std::uint64_t>());
  for (at::Tensor& p : r.predictions) {
    std::vector<std::int64_t> sizes(u.get<std::uint64_t>());
    for (std::int64_t& n : sizes) n = u.get<std::int64_t>();
    p = at::empty(sizes, at::kFloat);
    u.take(p.data_ptr<float>(), static_cast<std::size_t>(p.numel()) * sizeof(float));
  }
  return r;
}

// ---- what chose the checkpoint (docs/training.md, "Selection") ------------
json selection_of(const CheckpointState& state, const std::string& file, const std::string& evaluated_on) {
  const std::string name = std::filesystem::path(file).filename().string();
  const std::string kind = state.recorded                                 ? state.kind
                           : name == data::run_layout::checkpoint("best") ? "best"
                           : name == data::run_layout::checkpoint("last") ? "last"
                                                                          : "unknown";
  const std::string chosen_on = kind == "last"            ? "none"
                                : !state.recorded         ? "unknown"
                                : state.chosen_on.empty() ? "none"
                                                          : state.chosen_on;
  const bool chosen = kind != "last" && state.recorded && !state.chosen_on.empty();
  return {{"checkpoint", kind},
          {"chosen_on", chosen_on},
          {"evaluated_on", evaluated_on},
          {"chosen_epoch", chosen ? json(state.chosen_epoch) : json(nullptr)},
          {"epochs", state.recorded ? json(state.epochs) : json(nullptr)},
          {"metric", chosen ? json(state.metric) : json(nullptr)}};
}

// What the evaluation keeps of each sequence as it goes: the inputs of
// the summaries (per sequence, per garment type, per rollout step), the
// per-sequence entries of metrics.json and the rows of sequences.csv.
// Every metric is the registry's (its rules: metrics/registry.h).
struct EvalTally {
  const std::vector<metrics::MetricDef> defs = metrics::registered();  // the list as the evaluation starts
  Columns overall = Columns(defs.size()), truth = Columns(defs.size());
  std::map<std::string, Columns> per_type;  // garment type -> a value per garment and sequence
  std::vector<Columns> by_step;             // [step][metric][sequence]
  std::vector<std::size_t> step_sequences;  // sequences that reached each step
  json sequences = json::array();
  std::ostringstream csv;
  std::vector<double> growth_rates;  // mm per frame, per sequence (error growth)
  double model_seconds = 0;
  std::int64_t frames = 0, diverged = 0;

  EvalTally() {
    csv << "sequence,motion,tags,garment,type,layer,diverged_at";
    for (const metrics::MetricDef& d : defs) csv << ',' << d.key;
    csv << '\n';
  }

  // One evaluated sequence, in the split's order.
  void add(const SequenceRollout& r, const data::Dataset& dataset) {
    const std::string& id = r.id;
    const RolloutResult& res = r.result;
    model_seconds += res.model_seconds;
    frames += static_cast<std::int64_t>(res.frames.size());
    if (res.diverged_at >= 0) ++diverged;
    for (const FrameMetrics& m : res.frames)
      if (m.value.size() != defs.size() || m.truth.size() != defs.size())
        throw Error("evaluation of '" + id + "': a rollout measured " + std::to_string(m.value.size()) +
                    " metrics, the evaluation registers " + std::to_string(defs.size()) +
                    " (a metric registered while it ran, or ranks built differently)");
    if (by_step.size() < res.frames.size()) {
      by_step.resize(res.frames.size(), Columns(defs.size()));
      step_sequences.resize(res.frames.size(), 0);
    }
    std::vector<double> sequence(defs.size()), sequence_truth(defs.size(), kNaN);
    for (std::size_t k = 0; k < defs.size(); ++k) {
      std::vector<double> values, truths;
      for (std::size_t f = 0; f < res.frames.size(); ++f) {
        values.push_back(res.frames[f].value[k].scene);
        truths.push_back(res.frames[f].truth[k]);
        by_step[f][k].push_back(res.frames[f].value[k].scene);
      }
      sequence[k] = metrics::reduce_frames(defs[k], values);
      if (defs[k].truth) sequence_truth[k] = metrics::reduce_frames(defs[k], truths);
      overall[k].push_back(sequence[k]);
      if (defs[k].truth) truth[k].push_back(sequence_truth[k]);
    }
    for (std::size_t f = 0; f < res.frames.size(); ++f) ++step_sequences[f];
    const double growth = error_growth_mm_per_frame(res.frames);
    if (std::isfinite(growth)) growth_rates.push_back(growth);
    const data::SequenceInfo& info = dataset.info(id);
    std::string tags;
    for (const std::string& t : info.tags) tags += (tags.empty() ? "" : " ") + t;
    json garments = json::array();
    for (std::size_t g = 0; g < r.statics->garments.size(); ++g) {
      const zoo::GarmentStatic& gs = r.statics->garments[g];
      json garment = {{"name", gs.name}, {"type", gs.type}, {"layer", gs.layer}};
      Columns& type = per_type.try_emplace(gs.type, Columns(defs.size())).first->second;
      csv << id << ',' << info.motion << ',' << tags << ',' << gs.name << ',' << gs.type << ',' << gs.layer << ','
          << (res.diverged_at >= 0 ? std::to_string(res.diverged_at) : "");
      for (std::size_t k = 0; k < defs.size(); ++k) {
        std::vector<double> values;
        for (const FrameMetrics& m : res.frames)
          values.push_back(g < m.value[k].garments.size() ? m.value[k].garments[g] : kNaN);
        const double value = metrics::reduce_frames(defs[k], values);
        type[k].push_back(value);
        garment[defs[k].key] = number(value);
        csv << ',' << csv_number(value);
      }
      csv << '\n';
      garments.push_back(garment);
    }
    json entry = {{"id", id}, {"motion", info.motion}, {"tags", info.tags}, {"frames", res.frames.size()}};
    for (std::size_t k = 0; k < defs.size(); ++k) entry[defs[k].key] = number(sequence[k]);
    for (std::size_t k = 0; k < defs.size(); ++k)
      if (defs[k].truth) entry["truth_" + defs[k].key] = number(sequence_truth[k]);
    entry["diverged_at"] = res.diverged_at >= 0 ? json(res.diverged_at) : json(nullptr);
    entry["diverge_reason"] = res.diverge_reason;
    entry["error_growth_mm_per_frame"] = number(growth);
    entry["garments"] = garments;
    sequences.push_back(entry);
  }
};

// The report's summaries from the tally.
void summarise(const EvalTally& tally, EvalReport& report) {
  report.frames = tally.frames;
  report.diverged = tally.diverged;
  report.overall = summary_of(tally.overall, tally.defs);
  report.truth = summary_of(tally.truth, tally.defs);
  for (const auto& [type, columns] : tally.per_type)
    report.per_type.emplace_back(type, summary_of(columns, tally.defs));
  report.ms_per_frame = report.frames ? 1000.0 * tally.model_seconds / static_cast<double>(report.frames) : 0;
}

// metrics.json (docs/metrics.md).
json metrics_json(const EvalReport& report, const EvalTally& tally, const CheckpointState& state, const json& selection,
                  const ExperimentConfig& config, const std::string& dataset, int horizon, std::int64_t parameters) {
  json by_step = json::array();
  for (std::size_t f = 0; f < tally.by_step.size(); ++f) {
    json step = {{"step", f + 1}};
    for (std::size_t k = 0; k < tally.defs.size(); ++k)
      step[tally.defs[k].key] = number(metrics::finite_mean(tally.by_step[f][k]));
    step["sequences"] = tally.step_sequences[f];
    by_step.push_back(step);
  }
  json types = json::object();
  for (const auto& [type, summary] : report.per_type) types[type] = to_json(summary, tally.defs);
  json truth = json::object();
  for (const metrics::MetricDef& d : tally.defs)
    if (d.truth) {
      const metrics::MeanStd& t = report.truth.at(d.key);
      truth[d.key] = t.count ? number(t.mean) : json(nullptr);
    }
  return {{"model", report.model},
          {"checkpoint", report.checkpoint},
          // Ties these results to the exact checkpoint bytes they came from.
          {"checkpoint_fnv1a64", state.checksum},
          {"trained_epochs", state.epochs_done},
          {"selection", selection},
          {"experiment", config.source},
          {"dataset", dataset},
          {"split", report.split},
          {"subsets", config.data.subsets},
          {"inner_only", config.data.inner_only},
          // true: sequences without a recorded content hash were read unverified.
          {"allow_unhashed", config.data.allow_unhashed},
          {"horizon", horizon},
          {"diverge_mm", config.eval.diverge_mm},
          {"sequences", report.sequences},
          {"frames", report.frames},
          {"diverged", report.diverged},
          {"ms_per_frame", report.ms_per_frame},
          {"parameters", parameters},
          {"overall", to_json(report.overall, tally.defs)},
          {"error_growth_mm_per_frame", to_json(metrics::mean_std(tally.growth_rates))},
          {"truth", truth},
          {"per_type", types},
          {"by_step", by_step},
          {"per_sequence", tally.sequences}};
}

}  // namespace

std::string resolve_checkpoint(const ExperimentConfig& config, const std::string& which) {
  if (which == "best" || which == "last") return checkpoint_path(config, which);
  return which;
}

namespace {

// What is evaluated, and with what, checked before anything is written:
// the checkpoint and its selection, the split and its sequences (each
// passes the integrity check), the horizon and the output folder.
struct EvalPlan {
  CheckpointState state;
  json selection;
  int horizon = 0;
  std::vector<std::string> ids;
};

EvalPlan plan_evaluation(const ExperimentConfig& config, const EvalOptions& options, Session& s, bool root,
                         EvalReport& report) {
  EvalPlan plan;
  report.model = s.model->name();
  report.checkpoint = resolve_checkpoint(config, options.checkpoint);
  plan.state = load_checkpoint(report.checkpoint, *s.model, nullptr);
  s.model->train(false);
  report.split = evaluated_split(config, options.split);
  plan.selection = selection_of(plan.state, report.checkpoint, report.split);
  report.checkpoint_kind = plan.selection["checkpoint"].get<std::string>();
  report.chosen_on = plan.selection["chosen_on"].get<std::string>();
  if (data::run_layout::chosen_on_names(report.chosen_on, config.data.test_split))
    throw InputError(report.checkpoint, "selection.chosen_on",
                     "a checkpoint chosen on a split other than data.test_split '" + config.data.test_split + "'",
                     "one chosen on '" + report.chosen_on + "'");
  if (root && data::run_layout::chosen_on_names(report.chosen_on, report.split))
    spdlog::warn("{}: chosen on '{}', the split it is evaluated on: these figures are optimistic", report.checkpoint,
                 report.split);
  plan.horizon = options.horizon >= 0 ? options.horizon : config.eval.horizon;
  report.out_dir =
      !options.out_dir.empty()
          ? options.out_dir
          : (std::filesystem::path(config.run.output) / data::run_layout::eval_folder(report.split)).string();
  plan.ids =
      options.sequences.empty() ? select_sequences(s.dataset, report.split, config.data.subsets) : options.sequences;
  if (plan.ids.empty())
    throw InputError(s.dataset.path() + "/splits.yaml", report.split, "at least one sequence to evaluate", "none");
  for (const std::string& id : plan.ids)
    if (!s.dataset.contains(id))
      throw InputError(s.dataset.path(), "sequence '" + id + "'", "a sequence of the dataset", "unknown id");
  // Every evaluated sequence passes the integrity check before a file is written.
  s.dataset.verify(plan.ids);
  return plan;
}

// Rollouts of ids[first..first + ranks): one per rank; rank 0 gets them
// all, in the split's order (the other ranks get none).
std::vector<SequenceRollout> rollout_round(Session& s, dist::Group* group, const EvalPlan& plan, std::size_t first,
                                           const ExperimentConfig& config, bool keep_predictions) {
  std::vector<SequenceRollout> round;
  if (!group) {
    round.push_back(rollout_sequence(s, plan.ids[first], plan.horizon, config.eval.diverge_mm, keep_predictions));
    return round;
  }
  const auto rank = static_cast<std::size_t>(group->rank()), ranks = static_cast<std::size_t>(group->size());
  std::string mine;
  if (first + rank < plan.ids.size())
    mine = encode(
        rollout_sequence(s, plan.ids[first + rank], plan.horizon, config.eval.diverge_mm, config.eval.save_predictions)
            .result);
  const std::vector<std::string> all = group->gather(mine);
  for (std::size_t k = 0; group->is_root() && k < ranks && first + k < plan.ids.size(); ++k) {
    round.push_back(sequence_truth(s, plan.ids[first + k], plan.horizon));
    round.back().result = decode(all[k]);
  }
  return round;
}

}  // namespace

EvalReport run_evaluation(const ExperimentConfig& config, const zoo::Registry& registry, const EvalOptions& options) {
  dist::Group* group = options.group;
  const bool root = !group || group->is_root();
  const std::size_t ranks = group ? static_cast<std::size_t>(group->size()) : 1;
  Session s = open_session(config, registry, group ? group->local_rank() : -1, options.dataset);
  EvalReport report;
  const EvalPlan plan = plan_evaluation(config, options, s, root, report);
  if (root) std::filesystem::create_directories(report.out_dir);
  std::unique_ptr<data::ShardWriter> writer;
  if (config.eval.save_predictions && root)
    writer = std::make_unique<data::ShardWriter>(
        (std::filesystem::path(report.out_dir) / data::run_layout::kPredictions).string());
  EvalTally tally;
  std::optional<Progress> progress;
  if (root) progress.emplace("eval " + report.model + " on " + report.split, plan.ids.size(), "sequences");
  for (std::size_t first = 0; first < plan.ids.size(); first += ranks) {
    for (SequenceRollout& r : rollout_round(s, group, plan, first, config, writer != nullptr)) {
      tally.add(r, s.dataset);
      if (writer) writer->append(prediction_sequence(s.dataset, r, s.selection));
      char extra[64];
      std::snprintf(extra, sizeof extra, "error %.1f mm",
                    metrics::finite_mean(tally.overall[metrics::index_of(metrics::kError)]));
      if (options.progress && progress) progress->advance(1, extra);
    }
  }
  if (!root) return report;  // rank 0 reports and writes
  if (options.progress) progress->finish();
  if (writer) writer->commit();

  report.sequences = static_cast<std::int64_t>(plan.ids.size());
  summarise(tally, report);
  const json doc = metrics_json(report, tally, plan.state, plan.selection, config,
                                options.dataset.empty() ? config.data.dataset : options.dataset, plan.horizon,
                                s.model->info().parameters);
  write_text_atomic((std::filesystem::path(report.out_dir) / data::run_layout::kMetrics).string(), doc.dump(2) + "\n");
  write_text_atomic((std::filesystem::path(report.out_dir) / data::run_layout::kSequences).string(), tally.csv.str());
  return report;
}

}  // namespace layers::train
