// Golden metrics: extraction, files, tolerances and comparison (see
// golden_compare.h).
#include "golden_compare.h"

#include <nlohmann/json.hpp>

#include <cmath>
#include <cstdio>
#include <limits>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"

namespace layers::regression {
namespace {

using json = nlohmann::ordered_json;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

json parse(const std::string& text, const std::string& file) {
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    throw InputError(file, "", "JSON", std::string("malformed JSON: ") + e.what());
  }
}

double number(const json& v) { return v.is_number() ? v.get<double>() : kNaN; }

// The mean of a {mean, std, count} object (NaN when null or empty).
double mean_of(const json& stat) {
  if (!stat.is_object() || !stat.contains("mean")) return kNaN;
  if (stat.contains("count") && stat["count"].is_number() && stat["count"].get<double>() == 0) return kNaN;
  return number(stat["mean"]);
}

// Every metric of a summary object (a {mean, std, count} per registered
// metric: whatever the registry held when the file was written).
void add_summary(Metrics& out, const std::string& prefix, const json& summary) {
  for (const auto& [kind, stat] : summary.items())
    if (stat.is_object() && stat.contains("mean")) out[prefix + "." + kind] = mean_of(stat);
}

std::string format(double v) {
  if (std::isnan(v)) return "null";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string kind_of(const std::string& metric) {
  const auto dot = metric.rfind('.');
  return dot == std::string::npos ? metric : metric.substr(dot + 1);
}

}  // namespace

Metrics metrics_from_json(const std::string& json_text, const std::string& file) {
  const json doc = parse(json_text, file);
  if (!doc.is_object() || !doc.contains("overall") || !doc["overall"].is_object())
    throw InputError(file, "overall", "the evaluator's overall metrics", "nothing");
  Metrics out;
  add_summary(out, "overall", doc["overall"]);
  if (doc.contains("per_type") && doc["per_type"].is_object())
    for (const auto& [type, summary] : doc["per_type"].items()) add_summary(out, "per_type." + type, summary);
  if (doc.contains("diverged")) out["diverged"] = number(doc["diverged"]);
  if (doc.contains("error_growth_mm_per_frame"))
    out["error_growth_mm_per_frame"] = mean_of(doc["error_growth_mm_per_frame"]);
  return out;
}

Tolerance Tolerances::of(const std::string& metric) const {
  auto it = by_kind.find(kind_of(metric));
  if (it == by_kind.end())
    throw InputError("tests/regression/tolerances.yaml", kind_of(metric), "a tolerance for this metric kind",
                     "none (add one)");
  return it->second;
}

Tolerances read_tolerances(const std::string& yaml_file) {
  Tolerances t;
  t.by_kind = cfg::read<std::map<std::string, Tolerance>>(cfg::load_file(yaml_file));
  return t;
}

Golden read_golden(const std::string& file) {
  const json doc = parse(read_text_file(file), file);
  if (!doc.is_object() || !doc.contains("metrics") || !doc["metrics"].is_object())
    throw InputError(file, "metrics", "an object of metric values", "nothing");
  Golden g;
  g.run = doc.value("run", "");
  g.model = doc.value("model", "");
  for (const auto& [name, value] : doc["metrics"].items()) g.metrics[name] = number(value);
  return g;
}

std::string golden_json(const Golden& golden) {
  json metrics = json::object();
  for (const auto& [name, value] : golden.metrics) metrics[name] = std::isfinite(value) ? json(value) : json(nullptr);
  json doc = {{"run", golden.run},
              {"model", golden.model},
              {"note",
               "golden metrics of the CI regression (tests/regression); update on purpose with "
               "LAYERS_UPDATE_GOLDENS=1 (docs/studies.md)"},
              {"metrics", metrics}};
  return doc.dump(2) + "\n";
}

std::vector<std::string> compare(const Golden& golden, const Metrics& now, const Tolerances& tolerances) {
  std::vector<std::string> out;
  const std::string who = "run '" + golden.run + "' (model " + golden.model + "): ";
  for (const auto& [name, expected] : golden.metrics) {
    auto it = now.find(name);
    if (it == now.end()) {
      out.push_back(who + name + " missing: golden " + format(expected) + ", new run has no such metric");
      continue;
    }
    const double value = it->second;
    if (std::isnan(expected) || std::isnan(value)) {
      if (std::isnan(expected) != std::isnan(value))
        out.push_back(who + name + " moved: golden " + format(expected) + ", new " + format(value));
      continue;
    }
    const Tolerance tol = tolerances.of(name);
    const double allowed = tol.abs + tol.rel * std::fabs(expected);
    const double diff = value - expected;
    if (std::fabs(diff) <= allowed) continue;
    char buf[256];
    if (expected != 0)
      std::snprintf(buf, sizeof buf, " moved: golden %.6g, new %.6g, difference %+.4g (%+.1f%%), allowed +-%.4g",
                    expected, value, diff, 100.0 * diff / std::fabs(expected), allowed);
    else
      std::snprintf(buf, sizeof buf, " moved: golden %.6g, new %.6g, difference %+.4g, allowed +-%.4g", expected, value,
                    diff, allowed);
    out.push_back(who + name + buf);
  }
  // A metric whose kind has no tolerance is not guarded yet (one just added
  // to the registry): it becomes guarded with a tolerance and new goldens.
  for (const auto& [name, value] : now)
    if (!golden.metrics.count(name) && tolerances.by_kind.count(kind_of(name)))
      out.push_back(who + name + " is new: " + format(value) + ", not in the golden (update the goldens on purpose)");
  return out;
}

}  // namespace layers::regression
