// tests/regression/golden_compare.h -- golden metrics of the CI regression
// test: the numbers taken from an evaluator's metrics.json, the golden
// files (goldens/<run>.json) and the per-metric tolerances
// (tolerances.yaml), and the comparison that names the run, the metric, the
// golden value, the new value and the difference.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace layers::regression {

// Flat metric name -> value, e.g. "overall.error_mm", "per_type.jacket.h_collision",
// "diverged". NaN stands for a value metrics.json gives as null (e.g. no
// L-collision without an inner + outer pair).
using Metrics = std::map<std::string, double>;

// The compared metrics of a metrics.json text: every metric of its overall
// and per garment type summaries (the registry's, layers/metrics: means
// over sequences), the number of diverged sequences and the mean error
// growth rate. InputError naming
// `file` for malformed JSON or a missing overall section.
Metrics metrics_from_json(const std::string& json_text, const std::string& file);

// |new - golden| <= abs + rel * |golden|.
struct Tolerance {
  double abs = 0, rel = 0;
  template <class V>
  void visit(V& v) {
    v("abs", abs);
    v("rel", rel);
  }
};

// Tolerances by the last part of a metric name (error_mm, h_collision, ...).
struct Tolerances {
  std::map<std::string, Tolerance> by_kind;
  // The tolerance of a metric; InputError when its kind is not listed.
  Tolerance of(const std::string& metric) const;
};
Tolerances read_tolerances(const std::string& yaml_file);

struct Golden {
  std::string run, model;
  Metrics metrics;
};
Golden read_golden(const std::string& file);
// JSON text of a golden file (written with LAYERS_UPDATE_GOLDENS=1).
std::string golden_json(const Golden& golden);

// One readable line per metric out of tolerance, missing or unexpected (a
// new metric is unexpected only when its kind has a tolerance):
//   "run 'x' (model m): overall.error_mm moved: golden 7.61, new 9.02,
//    difference +1.41 (+18.5%), allowed +-0.20"
// Empty when everything is within tolerance.
std::vector<std::string> compare(const Golden& golden, const Metrics& now, const Tolerances& tolerances);

}  // namespace layers::regression
