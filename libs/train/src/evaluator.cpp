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
#include "layers/train/checkpoint.h"
#include "layers/train/session.h"
#include "layers/train/trainer.h"
#include "layers/train/window_loader.h"

namespace layers::train {
namespace {

using json = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// Mean of the finite values (NaN when none).
double finite_mean(const std::vector<double>& values) {
  double sum = 0;
  std::size_t n = 0;
  for (double v : values)
    if (std::isfinite(v)) sum += v, ++n;
  return n ? sum / static_cast<double>(n) : kNaN;
}

std::vector<double> finite_only(const std::vector<double>& values) {
  std::vector<double> out;
  for (double v : values)
    if (std::isfinite(v)) out.push_back(v);
  return out;
}

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }

json to_json(const zoo::MeanStd& m) { return {{"mean", number(m.mean)}, {"std", number(m.std)}, {"count", m.count}}; }

json to_json(const MetricSummary& s) {
  return {{"error_mm", to_json(s.error_mm)},       {"h_collision", to_json(s.h_collision)},
          {"l_collision", to_json(s.l_collision)}, {"l_collision_plain", to_json(s.l_collision_plain)},
          {"h_crossing", to_json(s.h_crossing)},   {"l_crossing", to_json(s.l_crossing)}};
}

// Per-sequence values gathered for the summaries.
struct Values {
  std::vector<double> error, h, l, hx, lx, lp;  // hx, lx: crossings; l: ours, lp: the paper's L-collision
  MetricSummary summary() const {
    return {zoo::mean_std(error),           zoo::mean_std(finite_only(h)),  zoo::mean_std(finite_only(l)),
            zoo::mean_std(finite_only(hx)), zoo::mean_std(finite_only(lx)), zoo::mean_std(finite_only(lp))};
  }
};

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
    if (m.diverged || !std::isfinite(m.error_mm)) break;
    const double x = static_cast<double>(m.frame);
    n += 1, sx += x, sy += m.error_mm, sxx += x * x, sxy += x * m.error_mm;
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
    b.put(m.frame), b.put(m.error_mm), b.put(m.garment_error_mm), b.put(m.garment_h_collision);
    b.put(m.h_collision), b.put(m.l_collision), b.put(m.truth_h_collision), b.put(m.truth_l_collision);
    b.put(m.garment_h_crossing), b.put(m.h_crossing), b.put(m.l_crossing), b.put(m.truth_h_crossing);
    b.put(m.truth_l_crossing), b.put(m.l_collision_plain), b.put(m.truth_l_collision_plain);
    b.put<std::uint8_t>(m.diverged);
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
    m.frame = u.get<std::int64_t>(), m.error_mm = u.get<double>();
    m.garment_error_mm = u.doubles(), m.garment_h_collision = u.doubles();
    m.h_collision = u.get<double>(), m.l_collision = u.get<double>();
    m.truth_h_collision = u.get<double>(), m.truth_l_collision = u.get<double>();
    m.garment_h_crossing = u.doubles(), m.h_crossing = u.get<double>(), m.l_crossing = u.get<double>();
    m.truth_h_crossing = u.get<double>(), m.truth_l_crossing = u.get<double>();
    m.l_collision_plain = u.get<double>(), m.truth_l_collision_plain = u.get<double>();
    m.diverged = u.get<std::uint8_t>() != 0;
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
struct EvalTally {
  Values overall, truth;
  std::map<std::string, Values> per_type;
  std::vector<std::vector<double>> step_error, step_h, step_l, step_hx, step_lx, step_lp;  // [step][sequence]
  json sequences = json::array();
  std::ostringstream csv;
  std::vector<double> growth_rates;  // mm per frame, per sequence (error growth)
  double model_seconds = 0;
  std::int64_t frames = 0, diverged = 0;

  EvalTally() {
    // New columns go at the end: scripts read the older ones by position.
    csv << "sequence,motion,tags,garment,type,layer,error_mm,h_collision,l_collision,diverged_at,h_crossing,l_crossing,"
           "l_collision_plain\n";
  }

  // One evaluated sequence, in the split's order.
  void add(const SequenceRollout& r, const data::Dataset& dataset) {
    const std::string& id = r.id;
    const RolloutResult& res = r.result;
    model_seconds += res.model_seconds;
    frames += static_cast<std::int64_t>(res.frames.size());
    if (res.diverged_at >= 0) ++diverged;
    std::vector<double> e, h, l, th, tl, hx, lx, thx, tlx, lp, tlp;
    for (std::size_t k = 0; k < res.frames.size(); ++k) {
      const FrameMetrics& m = res.frames[k];
      e.push_back(m.error_mm), h.push_back(m.h_collision), l.push_back(m.l_collision);
      th.push_back(m.truth_h_collision), tl.push_back(m.truth_l_collision);
      hx.push_back(m.h_crossing), lx.push_back(m.l_crossing);
      thx.push_back(m.truth_h_crossing), tlx.push_back(m.truth_l_crossing);
      lp.push_back(m.l_collision_plain), tlp.push_back(m.truth_l_collision_plain);
      if (step_error.size() <= k) {
        step_error.resize(k + 1), step_h.resize(k + 1), step_l.resize(k + 1);
        step_hx.resize(k + 1), step_lx.resize(k + 1), step_lp.resize(k + 1);
      }
      step_error[k].push_back(m.error_mm), step_h[k].push_back(m.h_collision), step_l[k].push_back(m.l_collision);
      step_hx[k].push_back(m.h_crossing), step_lx[k].push_back(m.l_crossing);
      step_lp[k].push_back(m.l_collision_plain);
    }
    const double seq_error = zoo::sequence_mean(e), seq_h = finite_mean(h), seq_l = finite_mean(l);
    const double seq_hx = finite_mean(hx), seq_lx = finite_mean(lx), seq_lp = finite_mean(lp);
    const double growth = error_growth_mm_per_frame(res.frames);
    if (std::isfinite(growth)) growth_rates.push_back(growth);
    overall.error.push_back(seq_error), overall.h.push_back(seq_h), overall.l.push_back(seq_l);
    overall.hx.push_back(seq_hx), overall.lx.push_back(seq_lx), overall.lp.push_back(seq_lp);
    truth.h.push_back(finite_mean(th)), truth.l.push_back(finite_mean(tl));
    truth.hx.push_back(finite_mean(thx)), truth.lx.push_back(finite_mean(tlx)), truth.lp.push_back(finite_mean(tlp));
    const data::SequenceInfo& info = dataset.info(id);
    std::string tags;
    for (const std::string& t : info.tags) tags += (tags.empty() ? "" : " ") + t;
    json garments = json::array();
    for (std::size_t g = 0; g < r.statics->garments.size(); ++g) {
      const zoo::GarmentStatic& gs = r.statics->garments[g];
      std::vector<double> ge, gh, ghx;
      for (const FrameMetrics& m : res.frames) {
        ge.push_back(m.garment_error_mm[g]);
        gh.push_back(m.diverged ? kNaN : m.garment_h_collision[g]);
        ghx.push_back(m.diverged ? kNaN : m.garment_h_crossing[g]);
      }
      const double g_error = zoo::sequence_mean(ge), g_h = finite_mean(gh), g_hx = finite_mean(ghx);
      // L-collision (both rules) and L-crossing belong to the outer garment
      const bool outer = gs.layer == 1;
      const double g_l = outer ? seq_l : kNaN, g_lx = outer ? seq_lx : kNaN, g_lp = outer ? seq_lp : kNaN;
      Values& type = per_type[gs.type];
      type.error.push_back(g_error), type.h.push_back(g_h), type.l.push_back(g_l);
      type.hx.push_back(g_hx), type.lx.push_back(g_lx), type.lp.push_back(g_lp);
      garments.push_back({{"name", gs.name},
                          {"type", gs.type},
                          {"layer", gs.layer},
                          {"error_mm", number(g_error)},
                          {"h_collision", number(g_h)},
                          {"l_collision", number(g_l)},
                          {"l_collision_plain", number(g_lp)},
                          {"h_crossing", number(g_hx)},
                          {"l_crossing", number(g_lx)}});
      csv << id << ',' << info.motion << ',' << tags << ',' << gs.name << ',' << gs.type << ',' << gs.layer << ','
          << csv_number(g_error) << ',' << csv_number(g_h) << ',' << csv_number(g_l) << ','
          << (res.diverged_at >= 0 ? std::to_string(res.diverged_at) : "") << ',' << csv_number(g_hx) << ','
          << csv_number(g_lx) << ',' << csv_number(g_lp) << '\n';
    }
    sequences.push_back({{"id", id},
                         {"motion", info.motion},
                         {"tags", info.tags},
                         {"frames", res.frames.size()},
                         {"error_mm", number(seq_error)},
                         {"h_collision", number(seq_h)},
                         {"l_collision", number(seq_l)},
                         {"l_collision_plain", number(seq_lp)},
                         {"truth_h_collision", number(truth.h.back())},
                         {"truth_l_collision", number(truth.l.back())},
                         {"truth_l_collision_plain", number(truth.lp.back())},
                         {"h_crossing", number(seq_hx)},
                         {"l_crossing", number(seq_lx)},
                         {"truth_h_crossing", number(truth.hx.back())},
                         {"truth_l_crossing", number(truth.lx.back())},
                         {"diverged_at", res.diverged_at >= 0 ? json(res.diverged_at) : json(nullptr)},
                         {"diverge_reason", res.diverge_reason},
                         {"error_growth_mm_per_frame", number(growth)},
                         {"garments", garments}});
  }
};

// The report's summaries from the tally.
void summarise(const EvalTally& tally, EvalReport& report) {
  const Values& overall = tally.overall;
  const Values& truth = tally.truth;
  report.frames = tally.frames;
  report.diverged = tally.diverged;
  report.overall = overall.summary();
  for (const auto& [type, values] : tally.per_type) report.per_type.emplace_back(type, values.summary());
  report.truth_h_collision = finite_mean(truth.h);
  report.truth_l_collision = finite_mean(truth.l);
  report.truth_h_crossing = finite_mean(truth.hx);
  report.truth_l_crossing = finite_mean(truth.lx);
  report.truth_l_collision_plain = finite_mean(truth.lp);
  report.ms_per_frame = report.frames ? 1000.0 * tally.model_seconds / static_cast<double>(report.frames) : 0;
}

// metrics.json (docs/metrics.md).
json metrics_json(const EvalReport& report, const EvalTally& tally, const CheckpointState& state, const json& selection,
                  const ExperimentConfig& config, int horizon, std::int64_t parameters) {
  json by_step = json::array();
  for (std::size_t k = 0; k < tally.step_error.size(); ++k) {
    by_step.push_back({{"step", k + 1},
                       {"error_mm", number(zoo::mean_std(tally.step_error[k]).mean)},
                       {"h_collision", number(finite_mean(tally.step_h[k]))},
                       {"l_collision", number(finite_mean(tally.step_l[k]))},
                       {"l_collision_plain", number(finite_mean(tally.step_lp[k]))},
                       {"h_crossing", number(finite_mean(tally.step_hx[k]))},
                       {"l_crossing", number(finite_mean(tally.step_lx[k]))},
                       {"sequences", tally.step_error[k].size()}});
  }
  json types = json::object();
  for (const auto& [type, summary] : report.per_type) types[type] = to_json(summary);
  return {{"model", report.model},
          {"checkpoint", report.checkpoint},
          // Ties these results to the exact checkpoint bytes they came from.
          {"checkpoint_fnv1a64", state.checksum},
          {"trained_epochs", state.epochs_done},
          {"selection", selection},
          {"experiment", config.source},
          {"dataset", config.data.dataset},
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
          {"overall", to_json(report.overall)},
          {"error_growth_mm_per_frame", to_json(zoo::mean_std(tally.growth_rates))},
          {"truth",
           {{"h_collision", number(report.truth_h_collision)},
            {"l_collision", number(report.truth_l_collision)},
            {"l_collision_plain", number(report.truth_l_collision_plain)},
            {"h_crossing", number(report.truth_h_crossing)},
            {"l_crossing", number(report.truth_l_crossing)}}},
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
  if (report.chosen_on == config.data.test_split)
    throw InputError(report.checkpoint, "selection.chosen_on",
                     "a checkpoint chosen on a split other than data.test_split '" + config.data.test_split + "'",
                     "one chosen on '" + report.chosen_on + "'");
  if (root && report.chosen_on == report.split)
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
    throw InputError(config.data.dataset + "/splits.yaml", report.split, "at least one sequence to evaluate", "none");
  for (const std::string& id : plan.ids)
    if (!s.dataset.contains(id))
      throw InputError(config.data.dataset, "sequence '" + id + "'", "a sequence of the dataset", "unknown id");
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
  Session s = open_session(config, registry, group ? group->local_rank() : -1);
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
      std::snprintf(extra, sizeof extra, "error %.1f mm", zoo::mean_std(tally.overall.error).mean);
      if (options.progress && progress) progress->advance(1, extra);
    }
  }
  if (!root) return report;  // rank 0 reports and writes
  if (options.progress) progress->finish();
  if (writer) writer->commit();

  report.sequences = static_cast<std::int64_t>(plan.ids.size());
  summarise(tally, report);
  const json doc =
      metrics_json(report, tally, plan.state, plan.selection, config, plan.horizon, s.model->info().parameters);
  write_text_atomic((std::filesystem::path(report.out_dir) / data::run_layout::kMetrics).string(), doc.dump(2) + "\n");
  write_text_atomic((std::filesystem::path(report.out_dir) / data::run_layout::kSequences).string(), tally.csv.str());
  return report;
}

}  // namespace layers::train
