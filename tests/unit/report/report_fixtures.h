// tests/unit/report/report_fixtures.h -- run folders written by the tests:
// metrics.json in the evaluator's format (libs/train/src/evaluator.cpp),
// bench.json in `layers bench`'s format, experiment.yaml.
#pragma once

#include <string>
#include <vector>

#include "temp_dir.h"

namespace layers::report::testing {

struct FakeRun {
  std::string model = "mymodel";
  double ms_per_frame = 2.0;
  double error = 10.0, error_std = 1.5;
  double h = 0.02, l = 0.05;
  // Exact crossings (h_crossing, l_crossing); false: a metrics.json written
  // before the evaluator measured them (no such keys anywhere).
  bool crossings = true;
  double hx = 0.004, lx = 0.006;
  // The paper's L-collision (l_collision_plain, beside our l_collision);
  // false: a metrics.json written before the evaluator measured it.
  bool plain = true;
  double lp = 0.08;
  std::vector<double> step_errors = {1.0, 2.0, 3.0};
  long diverged_at = -1;  // absolute frame of sequence s2, -1: stable
  std::string dataset = "/nonexistent/dataset";
  // metrics.json's `selection` (what chose the checkpoint); chosen_on "":
  // an evaluation made before the record (no such key).
  std::string chosen_on;
  std::string evaluated_on = "test";  // also metrics.json's split and the eval-<split> folder
  long parameters = 1234;             // 0: a reference model (nothing trained)
  // Per-sequence errors of sequences s1, s2, ... (s2 is the one that may diverge).
  std::vector<double> sequence_errors = {9.0, 11.0};
};

// metrics.json's per_sequence entries, one per sequence error.
inline std::string per_sequence_json(const FakeRun& r) {
  std::string out;
  for (std::size_t k = 0; k < r.sequence_errors.size(); ++k) {
    const bool diverged = k == 1 && r.diverged_at >= 0;
    out += std::string(k ? ",\n" : "") + "    {\"id\": \"s" + std::to_string(k + 1) + "\", \"motion\": \"" +
           (k == 1 ? "jump" : "walk") + "\", \"tags\": [\"" + (k == 1 ? "T+W" : "T") +
           "\"], \"frames\": 27, \"error_mm\": " + std::to_string(r.sequence_errors[k]) +
           ", \"h_collision\": 0.02, \"l_collision\": 0.05, \"truth_h_collision\": 0.0, \"truth_l_collision\": "
           "0.06, \"diverged_at\": " +
           (diverged ? std::to_string(r.diverged_at) : std::string("null")) + ", \"diverge_reason\": \"" +
           (diverged ? "non-finite prediction" : "") + "\", \"garments\": []}";
  }
  return out;
}

// `"selection": {...},` of metrics.json ("" without a record).
inline std::string selection_field(const FakeRun& r) {
  if (r.chosen_on.empty()) return "";
  return R"("selection": {"checkpoint": "best", "chosen_on": ")" + r.chosen_on + R"(", "evaluated_on": ")" +
         r.evaluated_on + R"x(", "chosen_epoch": 2, "epochs": 3, "metric": "mean rollout error (mm)"},)x";
}

inline std::string number_or_null(double v) { return v != v ? "null" : std::to_string(v); }

// `"key": {"mean": m, "std": s, "count": n}` preceded by a comma.
inline std::string stat_field(const std::string& key, double mean, double std, int count) {
  return ", \"" + key + "\": {\"mean\": " + std::to_string(mean) + ", \"std\": " + std::to_string(std) +
         ", \"count\": " + std::to_string(count) + "}";
}

// metrics.json as the evaluator writes it: two sequences, a jumpsuit
// (inner, no L-collision: count 0) and a jacket.
inline std::string metrics_json(const FakeRun& r) {
  const auto crossing = [&](double hx, double lx, int l_count) {
    return r.crossings ? stat_field("h_crossing", hx, 0.001, 2) + stat_field("l_crossing", lx, 0.002, l_count)
                       : std::string();
  };
  const auto plain = [&](double lp, double std, int count) {
    return r.plain ? stat_field("l_collision_plain", lp, std, count) : std::string();
  };
  std::string steps;
  for (std::size_t k = 0; k < r.step_errors.size(); ++k)
    steps += std::string(k ? "," : "") + "{\"step\": " + std::to_string(k + 1) +
             ", \"error_mm\": " + std::to_string(r.step_errors[k]) + ", \"h_collision\": " + std::to_string(r.h) +
             ", \"l_collision\": " + (k == 0 ? "null" : std::to_string(r.l)) +
             (r.crossings ? ", \"h_crossing\": " + std::to_string(r.hx) +
                                ", \"l_crossing\": " + (k == 0 ? "null" : std::to_string(r.lx))
                          : std::string()) +
             (r.plain ? ", \"l_collision_plain\": " + (k == 0 ? "null" : std::to_string(r.lp)) : std::string()) +
             ", \"sequences\": 2}";
  return R"({
  "model": ")" +
         r.model + R"(",
  "checkpoint": "x/checkpoint-best.pt", "trained_epochs": 3, "experiment": "e.yaml", )" +
         selection_field(r) + R"(
  "dataset": ")" +
         r.dataset + R"(", "split": ")" + r.evaluated_on + R"(", "subsets": [], "inner_only": false,
  "horizon": 27, "diverge_mm": 1000.0, "sequences": 2, "frames": 54,
  "diverged": )" +
         std::string(r.diverged_at >= 0 ? "1" : "0") + R"(,
  "ms_per_frame": )" +
         std::to_string(r.ms_per_frame) + R"(, "parameters": )" + std::to_string(r.parameters) + R"(,
  "overall": {"error_mm": {"mean": )" +
         std::to_string(r.error) + R"(, "std": )" + std::to_string(r.error_std) +
         R"(, "count": 2},
              "h_collision": {"mean": )" +
         std::to_string(r.h) + R"(, "std": 0.01, "count": 2},
              "l_collision": {"mean": )" +
         std::to_string(r.l) + R"(, "std": 0.0, "count": 2})" + crossing(r.hx, r.lx, 2) + plain(r.lp, 0.01, 2) + R"(},
  "truth": {"h_collision": 0.0, "l_collision": 0.0645)" +
         std::string(r.crossings ? R"(, "h_crossing": 0.0, "l_crossing": 0.0025)" : "") +
         std::string(r.plain ? R"(, "l_collision_plain": 0.0845)" : "") + R"(},
  "per_type": {
    "jacket": {"error_mm": {"mean": )" +
         std::to_string(r.error + 1) + R"(, "std": 0.5, "count": 2},
               "h_collision": {"mean": 0.01, "std": 0.0, "count": 2},
               "l_collision": {"mean": )" +
         std::to_string(r.l) + R"(, "std": 0.0, "count": 2})" + crossing(0.003, r.lx, 2) + plain(r.lp, 0.0, 2) +
         R"(},
    "jumpsuit": {"error_mm": {"mean": )" +
         std::to_string(r.error - 1) + R"(, "std": 0.5, "count": 2},
                 "h_collision": {"mean": 0.03, "std": 0.0, "count": 2},
                 "l_collision": {"mean": 0.0, "std": 0.0, "count": 0})" +
         crossing(0.005, 0.0, 0) + plain(0.0, 0.0, 0) + R"(}},
  "by_step": [)" +
         steps + R"(],
  "per_sequence": [
)" + per_sequence_json(r) +
         R"(]
}
)";
}

inline std::string bench_json(const std::string& model, double ms0, double ms1) {
  return R"({"model": ")" + model + R"(", "parameters": 1234, "threads": 2, "sequence": "s1",
  "dataset": "d", "experiment": "e.yaml", "rows": [
  {"level": 0, "far_body": false, "garment_vertices": 300, "body_vertices": 200, "counters": {"patches": 12},
   "ms_per_frame": )" +
         std::to_string(ms0) + R"(, "train_ms_per_frame": 0.0},
  {"level": 0, "far_body": true, "garment_vertices": 300, "body_vertices": 400, "counters": {"patches": 12},
   "ms_per_frame": )" +
         std::to_string(ms0) + R"(, "train_ms_per_frame": 0.0},
  {"level": 1, "far_body": false, "garment_vertices": 1200, "body_vertices": 200, "counters": {},
   "ms_per_frame": )" +
         std::to_string(ms1) + R"(, "train_ms_per_frame": 4.5}]}
)";
}

// A run folder <root>/<name> with experiment.yaml and eval-<evaluated_on>/metrics.json.
inline std::string write_run(const layers::test::TempDir& root, const std::string& name, const FakeRun& r) {
  root.write(name + "/experiment.yaml", "run: {output: " + root.file(name) + "}\ndata: {dataset: " + r.dataset +
                                            "}\nmodel: {name: " + r.model + ", params: {}}\n");
  root.write(name + "/eval-" + r.evaluated_on + "/metrics.json", metrics_json(r));
  return root.file(name);
}

}  // namespace layers::report::testing
