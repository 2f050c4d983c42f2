// The report's CSV and JSON tables (see tables.h).
#include "layers/report/tables.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <sstream>

#include "layers/report/pareto.h"
#include "layers/report/seeds.h"
#include "text.h"

namespace layers::report {
namespace {

using json = nlohmann::ordered_json;

std::vector<ParetoPoint> speed_points(const std::vector<RunResults>& runs) {
  std::vector<ParetoPoint> points;
  for (const RunResults& r : runs)
    points.push_back(r.eval ? ParetoPoint{r.eval->ms_per_frame, r.eval->overall.error_mm.mean}
                            : ParetoPoint{kAbsent, kAbsent});
  return points;
}

json number(double v) { return std::isfinite(v) ? json(v) : json(nullptr); }
json to_json(const Stat& s) { return {{"mean", number(s.mean)}, {"std", number(s.std)}, {"count", s.count}}; }
json to_json(const MetricStats& m) {
  return {{"error_mm", to_json(m.error_mm)},       {"h_collision", to_json(m.h_collision)},
          {"l_collision", to_json(m.l_collision)}, {"l_collision_plain", to_json(m.l_collision_plain)},
          {"h_crossing", to_json(m.h_crossing)},   {"l_crossing", to_json(m.l_crossing)}};
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
  out << "run,model,split,sequences,frames,parameters,ms_per_frame,error_mm_mean,error_mm_std,h_collision,"
         "h_collision_std,l_collision,l_collision_std,truth_h_collision,truth_l_collision,diverged,"
         "first_divergence_step,pareto,h_crossing,h_crossing_std,l_crossing,l_crossing_std,truth_h_crossing,"
         "truth_l_crossing,l_collision_plain,l_collision_plain_std,truth_l_collision_plain,checkpoint,chosen_on,"
         "evaluated_on,chosen_epoch,epochs,val_error_mm,selection_flag,experiment,seed\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const RunResults& r = runs[i];
    if (!r.eval) continue;
    const EvalResults& e = *r.eval;
    const std::int64_t div = e.first_divergence_step();
    out << csv_field(r.name) << ',' << csv_field(r.model) << ',' << csv_field(e.split) << ',' << e.sequences << ','
        << e.frames << ',' << e.parameters << ',' << exact(e.ms_per_frame) << ',' << exact(e.overall.error_mm.mean)
        << ',' << exact(e.overall.error_mm.std) << ',' << exact(e.overall.h_collision.mean) << ','
        << exact(e.overall.h_collision.std) << ',' << exact(e.overall.l_collision.mean) << ','
        << exact(e.overall.l_collision.std) << ',' << exact(e.truth_h_collision) << ',' << exact(e.truth_l_collision)
        << ',' << e.diverged << ',' << (div >= 0 ? std::to_string(div) : "") << ',' << (front[i] ? "yes" : "no") << ','
        << exact(e.overall.h_crossing.mean) << ',' << exact(e.overall.h_crossing.std) << ','
        << exact(e.overall.l_crossing.mean) << ',' << exact(e.overall.l_crossing.std) << ','
        << exact(e.truth_h_crossing) << ',' << exact(e.truth_l_crossing) << ','
        << exact(e.overall.l_collision_plain.mean) << ',' << exact(e.overall.l_collision_plain.std) << ','
        << exact(e.truth_l_collision_plain) << ',' << selection_cells(r) << '\n';
  }
  return out.str();
}

std::string per_type_csv(const std::vector<RunResults>& runs) {
  std::ostringstream out;
  out << "run,model,type,sequences,error_mm_mean,error_mm_std,h_collision,h_collision_std,l_collision,"
         "l_collision_std,h_crossing,h_crossing_std,l_crossing,l_crossing_std,l_collision_plain,l_collision_plain_"
         "std\n";
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    for (const auto& [type, m] : r.eval->per_type)
      out << csv_field(r.name) << ',' << csv_field(r.model) << ',' << csv_field(type) << ',' << m.error_mm.count << ','
          << exact(m.error_mm.mean) << ',' << exact(m.error_mm.std) << ',' << exact(m.h_collision.mean) << ','
          << exact(m.h_collision.std) << ',' << exact(m.l_collision.mean) << ',' << exact(m.l_collision.std) << ','
          << exact(m.h_crossing.mean) << ',' << exact(m.h_crossing.std) << ',' << exact(m.l_crossing.mean) << ','
          << exact(m.l_crossing.std) << ',' << exact(m.l_collision_plain.mean) << ',' << exact(m.l_collision_plain.std)
          << '\n';
  }
  return out.str();
}

std::string by_step_csv(const std::vector<RunResults>& runs) {
  std::ostringstream out;
  out << "run,model,step,error_mm,h_collision,l_collision,sequences,h_crossing,l_crossing,l_collision_plain\n";
  for (const RunResults& r : runs) {
    if (!r.eval) continue;
    for (const StepMetrics& s : r.eval->by_step)
      out << csv_field(r.name) << ',' << csv_field(r.model) << ',' << s.step << ',' << exact(s.error_mm) << ','
          << exact(s.h_collision) << ',' << exact(s.l_collision) << ',' << s.sequences << ',' << exact(s.h_crossing)
          << ',' << exact(s.l_crossing) << ',' << exact(s.l_collision_plain) << '\n';
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
                      {"truth",
                       {{"h_collision", number(e.truth_h_collision)},
                        {"l_collision", number(e.truth_l_collision)},
                        {"l_collision_plain", number(e.truth_l_collision_plain)},
                        {"h_crossing", number(e.truth_h_crossing)},
                        {"l_crossing", number(e.truth_l_crossing)}}},
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
                      {"error_mm", runs[i].eval->overall.error_mm.mean}});
  const json doc = {{"title", title},
                    {"units",
                     {{"error", "mm (real world; the paper's mm are 10x)"},
                      {"rates", "share 0..1"},
                      {"time", "ms per predicted frame"}}},
                    {"runs", rows},
                    {"pareto_front", pareto},
                    {"seeds", seeds_json(runs)},
                    {"problems", problems},
                    {"charts", charts}};
  return doc.dump(2) + "\n";
}

}  // namespace layers::report
