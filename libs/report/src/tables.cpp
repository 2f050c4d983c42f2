// The report's CSV and JSON tables (see tables.h).
#include "layers/report/tables.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

#include "layers/metrics/registry.h"
#include "layers/report/pareto.h"
#include "layers/report/seeds.h"
#include "text.h"

namespace layers::report {
namespace {

using json = nlohmann::ordered_json;

std::vector<ParetoPoint> speed_points(const std::vector<RunResults>& runs) {
  std::vector<ParetoPoint> points;
  for (const RunResults& r : runs)
    points.push_back(r.eval ? ParetoPoint{r.eval->ms_per_frame, r.eval->overall.get(metrics::kError).mean}
                            : ParetoPoint{kAbsent, kAbsent});
  return points;
}

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json to_json(const Stat& s) { return {{"mean", number(s.mean)}, {"std", number(s.std)}, {"count", s.count}}; }
// Every registered metric, in registry order.
json to_json(const MetricStats& m) {
  json out = json::object();
  for (const metrics::MetricDef& d : metrics::registered()) out[d.key] = to_json(m.get(d.key));
  return out;
}

json truth_json(const EvalResults& e) {
  json out = json::object();
  for (const metrics::MetricDef& d : metrics::registered())
    if (d.truth) out[d.key] = number(e.truth_of(d.key));
  return out;
}

// What each metric is (summary.json's `metrics`).
json registry_json() {
  json out = json::array();
  for (const metrics::MetricDef& d : metrics::registered())
    out.push_back({{"key", d.key},
                   {"label", d.label},
                   {"unit", d.unit == metrics::Unit::Millimetre ? "mm" : "share 0..1"},
                   {"better", d.better == metrics::Better::Lower ? "lower" : "higher"},
                   {"scope", d.scope == metrics::Scope::OuterLayer ? "outer garments" : "every garment"},
                   {"truth", d.truth},
                   {"description", d.description},
                   {"rule", "docs/metrics.md: " + d.rule}});
  return out;
}

// `,<key>,<key>_std` per registered metric (CSV header cells).
std::string stat_headers() {
  std::string out;
  for (const metrics::MetricDef& d : metrics::registered()) out += "," + d.key + "," + d.key + "_std";
  return out;
}

std::string stat_cells(const MetricStats& m) {
  std::string out;
  for (const metrics::MetricDef& d : metrics::registered())
    out += "," + exact(m.get(d.key).mean) + "," + exact(m.get(d.key).std);
  return out;
}

std::string counters_text(const std::map<std::string, double>& counters) {
  std::string out;
  for (const auto& [k, v] : counters) out += (out.empty() ? "" : ";") + k + "=" + exact(v);
  return out;
}

// summary.csv's selection and seed columns of a run.
std::string selection_cells(const RunResults& r) {
  const SelectionRecord& s = r.eval->selection;
  std::ostringstream out;
  out << csv_field(s.checkpoint) << ',' << csv_field(s.chosen_on) << ',' << csv_field(s.evaluated_on) << ','
      << (s.chosen_epoch > 0 ? std::to_string(s.chosen_epoch) : "") << ','
      << (s.epochs > 0 ? std::to_string(s.epochs) : "") << ',' << exact(s.val_error_mm) << ','
      << csv_field(selection_flag(r)) << ',' << csv_field(r.experiment) << ','
      << (r.repeated ? std::to_string(r.seed) : "");
  return out.str();
}

json selection_json(const RunResults& r) {
  const SelectionRecord& s = r.eval->selection;
  return {{"checkpoint", s.checkpoint},
          {"chosen_on", s.chosen_on},
          {"evaluated_on", s.evaluated_on},
          {"chosen_epoch", s.chosen_epoch > 0 ? json(s.chosen_epoch) : json(nullptr)},
          {"epochs", s.epochs > 0 ? json(s.epochs) : json(nullptr)},
          {"metric", s.metric},
          {"val_error_mm", std::isfinite(s.val_error_mm) ? json(s.val_error_mm) : json(nullptr)},
          {"flag", selection_flag(r)}};
}

json seeds_json(const std::vector<RunResults>& runs) {
  json out = json::array();
  for (const SeedGroup& g : seed_groups(runs)) {
    json members = json::array();
    for (std::size_t i : g.runs) members.push_back(runs[i].name);
    out.push_back({{"experiment", g.experiment},
                   {"model", g.model},
                   {"split", g.split},
                   {"seeds", g.seeds},
                   {"runs", members},
                   {"sequences", g.sequences},
                   {"over_seeds", to_json(g.over_seeds)},
                   {"std_over_sequences", to_json(g.over_sequences)},
                   {"ms_per_frame", number(g.ms_per_frame)},
                   {"diverged", g.diverged}});
  }
  return out;
}

}  // namespace

std::vector<bool> runs_on_front(const std::vector<RunResults>& runs) { return pareto_front(speed_points(runs)); }

std::vector<std::size_t> runs_front_order(const std::vector<RunResults>& runs) {
  return pareto_order(speed_points(runs));
}

std::string summary_csv(const std::vector<RunResults>& runs) {
  const std::vector<bool> front = runs_on_front(runs);
  std::ostringstream out;
  out << "run,model,split,sequences,frames,parameters,ms_per_frame" << stat_headers();
  for (const metrics::MetricDef& d : metrics::registered())
    if (d.truth) out << ",truth_" << d.key;
  out << ",diverged,first_divergence_step,pareto,checkpoint,chosen_on,evaluated_on,chosen_epoch,epochs,val_error_mm,"
         "selection_flag,experiment,seed\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResults& r = runs[i];
    if (!r.eval) continue;
    const EvalResults& e = *r.eval;
    const std::int64_t div = e.first_divergence_step();
    out << csv_field(r.name) << ',' << csv_field(r.model) << ',' << csv_field(e.split) << ',' << e.sequences << ','
        << e.frames << ',' << e.parameters << ',' << exact(e.ms_per_frame) << stat_cells(e.overall);
    for (const metrics::MetricDef& d : metrics::registered())
      if (d.truth) out << ',' << exact(e.truth_of(d.key));
    out << ',' << e.diverged << ',' << (div >= 0 ? std::to_string(div) : "") << ',' << (front[i] ? "yes" : "no") << ','
        << selection_cells(r) << '\n';
  }
  return out.str();
}

std::string per_type_csv(const std::vector<RunResults>& runs) {
  std::ostringstream out;
  out << "run,model,type,sequences" << stat_headers() << "\n";
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    for (const auto& [type, m] : r.eval->per_type)
      out << csv_field(r.name) << ',' << csv_field(r.model) << ',' << csv_field(type) << ','
          << m.get(metrics::kError).count << stat_cells(m) << '\n';
  }
  return out.str();
}

std::string by_step_csv(const std::vector<RunResults>& runs) {
  std::ostringstream out;
  out << "run,model,step,sequences";
  for (const metrics::MetricDef& d : metrics::registered()) out << ',' << d.key;
  out << "\n";
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    for (const StepMetrics& s : r.eval->by_step) {
      out << csv_field(r.name) << ',' << csv_field(r.model) << ',' << s.step << ',' << s.sequences;
      for (const metrics::MetricDef& d : metrics::registered()) out << ',' << exact(s.get(d.key));
      out << '\n';
    }
  }
  return out.str();
}

std::string bench_csv(const std::vector<RunResults>& runs) {
  std::ostringstream out;
  out << "run,model,level,far_body,garment_vertices,body_vertices,ms_per_frame,train_ms_per_frame,counters\n";
  for (const RunResults& r : runs) {
    if (!r.bench) continue;
    for (const BenchPoint& b : r.bench->rows)
      out << csv_field(r.name) << ',' << csv_field(r.bench->model) << ',' << b.level << ','
          << (b.far_body ? "yes" : "no") << ',' << b.garment_vertices << ',' << b.body_vertices << ','
          << exact(b.ms_per_frame) << ',' << exact(b.train_ms_per_frame) << ',' << csv_field(counters_text(b.counters))
          << '\n';
  }
  return out.str();
}

std::string summary_json(const std::string& title, const std::vector<RunResults>& runs,
                         const std::vector<std::string>& problems, const std::vector<std::string>& charts) {
  const std::vector<bool> front = runs_on_front(runs);
  json rows = json::array();
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResults& r = runs[i];
    json row = {{"run", r.name},
                {"dir", r.dir},
                {"model", r.model},
                {"dataset", r.dataset},
                {"experiment", r.experiment},
                {"seed", r.repeated ? json(r.seed) : json(nullptr)}};
    if (r.eval) {
      const EvalResults& e = *r.eval;
      const std::int64_t div = e.first_divergence_step();
      json types = json::object();
      for (const auto& [type, m] : e.per_type) types[type] = to_json(m);
      row.update(json{{"split", e.split},
                      {"sequences", e.sequences},
                      {"frames", e.frames},
                      {"parameters", e.parameters},
                      {"ms_per_frame", number(e.ms_per_frame)},
                      {"overall", to_json(e.overall)},
                      {"truth", truth_json(e)},
                      {"diverged", e.diverged},
                      {"first_divergence_step", div >= 0 ? json(div) : json(nullptr)},
                      {"pareto", static_cast<bool>(front[i])},
                      {"per_type", types},
                      {"selection", selection_json(r)}});
    } else {
      row["overall"] = nullptr;
    }
    json bench = json::array();
    if (r.bench)
      for (const BenchPoint& b : r.bench->rows)
        bench.push_back({{"level", b.level},
                         {"far_body", b.far_body},
                         {"garment_vertices", b.garment_vertices},
                         {"body_vertices", b.body_vertices},
                         {"ms_per_frame", number(b.ms_per_frame)},
                         {"train_ms_per_frame", number(b.train_ms_per_frame)},
                         {"counters", b.counters}});
    row["bench"] = bench;
    rows.push_back(row);
  }
  json pareto = json::array();
  for (std::size_t i : runs_front_order(runs))
    pareto.push_back({{"run", runs[i].name},
                      {"model", runs[i].model},
                      {"ms_per_frame", runs[i].eval->ms_per_frame},
                      {"error_mm", runs[i].eval->overall.get(metrics::kError).mean}});
  const json doc = {{"title", title},
                    {"units",
                     {{"error", "mm (real world; the paper's mm are 10x)"},
                      {"rates", "share 0..1"},
                      {"time", "ms per predicted frame"}}},
                    {"metrics", registry_json()},
                    {"runs", rows},
                    {"pareto_front", pareto},
                    {"seeds", seeds_json(runs)},
                    {"problems", problems},
                    {"charts", charts}};
  return doc.dump(2) + "\n";
}

}  // namespace layers::report
