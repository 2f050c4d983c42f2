// The evaluation metrics, declared once (see registry.h).
#include "layers/metrics/registry.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

#include "layers/core/error.h"

namespace layers::metrics {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// ---- the built-in metrics' frame measures ----------------------------------

// Mean distance to the ground truth (mm), per garment and over every vertex.
FrameValue error_of(const FrameScene& s) {
  return vertex_weighted(s, [&](std::size_t g) { return euclidean_error_mm(s.garment(g).vertices, s.truth(g)); });
}

// Share of garment vertices behind the body surface.
FrameValue h_collision_of(const FrameScene& s) {
  return vertex_weighted(
      s, [&](std::size_t g) { return behind_share(s.garment(g).vertices, s.body().surface()); }, 0.0);
}

// A scene value given to the outer garments (Scope::OuterLayer).
FrameValue outer_value(const FrameScene& s, double scene) {
  FrameValue v{scene, {}};
  for (std::size_t g = 0; g < s.size(); ++g) v.garments.push_back(s.outer(g) ? scene : kNaN);
  return v;
}

FrameValue l_collision_of(const FrameScene& s) { return outer_value(s, s.has_layers() ? s.l_collision().ours : kNaN); }

FrameValue l_collision_plain_of(const FrameScene& s) {
  return outer_value(s, s.has_layers() ? s.l_collision().plain : kNaN);
}

// Share of garment vertices on a face through the body; each garment's
// share is its slice of the per-vertex flags.
FrameValue h_crossing_of(const FrameScene& s) {
  const geometry::MeshCrossings& h = s.body_crossings();
  FrameValue v{h.a_vertex_share(), {}};
  std::size_t first = 0;
  for (const geometry::TriMesh& m : s.garments()) {
    const auto n = static_cast<std::size_t>(m.num_vertices());
    std::int64_t on = 0;
    for (std::size_t k = first; k < first + n && k < h.a_vertices.size(); ++k) on += h.a_vertices[k] ? 1 : 0;
    v.garments.push_back(n ? static_cast<double>(on) / static_cast<double>(n) : 0.0);
    first += n;
  }
  return v;
}

FrameValue l_crossing_of(const FrameScene& s) {
  return outer_value(s, s.has_layers() ? s.layer_crossings().a_vertex_share() : kNaN);
}

std::vector<MetricDef> built_in() {
  std::vector<MetricDef> defs;
  MetricDef error;
  error.key = kError;
  error.label = "error (mm)";
  error.axis = "mean Euclidean error (mm)";
  error.description =
      "mean Euclidean distance between predicted and true garment vertices, averaged over each rollout "
      "(frames after a divergence count as the bound)";
  error.rule = "Euclidean error";
  error.unit = Unit::Millimetre;
  error.diverged = Diverged::Bound;
  error.compute = error_of;
  defs.push_back(error);

  MetricDef h;
  h.key = "h_collision";
  h.label = "H-collision";
  h.axis = "garment vertices behind the body (%)";
  h.description =
      "share of garment vertices behind the body surface (the normal plane of the nearest body vertex, as in the "
      "paper)";
  h.rule = "H-collision (garment vs body)";
  h.truth = true;
  h.compute = h_collision_of;
  defs.push_back(h);

  MetricDef l;
  l.key = "l_collision";
  l.label = "L-coll (ours: open-edge rule)";
  l.axis = "outer-garment vertices behind the inner garment (%)";
  l.description =
      "share of outer-garment vertices behind the inner garment, except those whose nearest inner vertex lies on "
      "an open edge of the inner garment (a hem, a cuff): beside it, not behind (ours)";
  l.rule = "L-collision (outer vs inner layer): the paper's and ours";
  l.scope = Scope::OuterLayer;
  l.truth = true;
  l.compute = l_collision_of;
  defs.push_back(l);

  MetricDef lp = l;
  lp.key = "l_collision_plain";
  lp.label = "L-coll (paper: nearest vertex)";
  lp.description =
      "share of outer-garment vertices behind the normal plane of their nearest inner vertex (the paper's "
      "L-collision, comparable with its figures)";
  lp.compute = l_collision_plain_of;
  defs.push_back(lp);

  MetricDef hx;
  hx.key = "h_crossing";
  hx.label = "H-crossing";
  hx.axis = "garment vertices on faces through the body (%)";
  hx.description =
      "share of garment vertices on a garment face that passes through a body face (exact; touching does not "
      "count)";
  hx.rule = "H-crossing and L-crossing";
  hx.truth = true;
  hx.compute = h_crossing_of;
  defs.push_back(hx);

  MetricDef lx = hx;
  lx.key = "l_crossing";
  lx.label = "L-crossing";
  lx.axis = "outer-garment vertices on faces through the inner garment (%)";
  lx.description = "share of outer-garment vertices on an outer face that passes through an inner-garment face (exact)";
  lx.scope = Scope::OuterLayer;
  lx.compute = l_crossing_of;
  defs.push_back(lx);
  return defs;
}

std::vector<MetricDef>& table() {
  static std::vector<MetricDef> defs = built_in();
  return defs;
}

constexpr std::size_t kBuiltIn = 6;

bool snake_case(const std::string& key) {
  if (key.empty() || !(key[0] >= 'a' && key[0] <= 'z')) return false;
  return std::all_of(key.begin(), key.end(),
                     [](char c) { return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_'; });
}

}  // namespace

FrameValue vertex_weighted(const FrameScene& s, const std::function<double(std::size_t)>& per_garment,
                           double if_empty) {
  FrameValue v;
  double sum = 0, count = 0;
  for (std::size_t g = 0; g < s.size(); ++g) {
    const double value = per_garment(g);
    const double n = static_cast<double>(s.garment(g).num_vertices());
    v.garments.push_back(value);
    sum += value * n;
    count += n;
  }
  v.scene = count > 0 ? sum / count : if_empty;
  return v;
}

const std::vector<MetricDef>& registered() { return table(); }

std::size_t index_of(const std::string& key) {
  const std::vector<MetricDef>& defs = table();
  for (std::size_t k = 0; k < defs.size(); ++k)
    if (defs[k].key == key) return k;
  throw Error("metric '" + key + "' is not registered (libs/metrics registry.h)");
}

const MetricDef& metric(const std::string& key) { return table()[index_of(key)]; }

void add(MetricDef def) {
  if (!snake_case(def.key)) throw Error("metric key '" + def.key + "': expected lower_snake_case");
  if (def.key.rfind("truth_", 0) == 0) throw Error("metric key '" + def.key + "': truth_ names the ground truth's");
  for (const MetricDef& d : table())
    if (d.key == def.key) throw Error("metric '" + def.key + "' is registered already");
  if (!def.compute) throw Error("metric '" + def.key + "': no function to measure a frame");
  if (def.diverged == Diverged::Bound && def.unit != Unit::Millimetre)
    throw Error("metric '" + def.key +
                "': a diverged frame counts as the divergence bound (mm) only for a metric in mm");
  if (def.label.empty()) def.label = def.key;
  if (def.axis.empty()) def.axis = def.label;
  table().push_back(std::move(def));
}

void remove(const std::string& key) {
  const std::size_t k = index_of(key);
  if (k < kBuiltIn) throw Error("metric '" + key + "' is built in and stays registered");
  table().erase(table().begin() + static_cast<std::ptrdiff_t>(k));
}

ScopedMetric::ScopedMetric(MetricDef def) : key_(def.key) { add(std::move(def)); }
ScopedMetric::~ScopedMetric() {
  try {
    remove(key_);
  } catch (...) {
  }
}

double finite_mean(const std::vector<double>& values) {
  double sum = 0;
  std::size_t n = 0;
  for (double v : values)
    if (std::isfinite(v)) sum += v, ++n;
  return n ? sum / static_cast<double>(n) : kNaN;
}

MeanStd finite_mean_std(const std::vector<double>& values) {
  std::vector<double> finite;
  for (double v : values)
    if (std::isfinite(v)) finite.push_back(v);
  return mean_std(finite);
}

double reduce_frames(const MetricDef& def, const std::vector<double>& values) {
  if (def.frames == Reduce::Mean) return finite_mean(values);
  double best = kNaN;
  for (double v : values)
    if (std::isfinite(v) && !(v <= best)) best = v;
  return best;
}

std::string format_value(const MetricDef& def, const MeanStd& value) {
  if (value.count == 0) return "-";
  char buf[96];
  if (def.unit == Unit::Millimetre && std::isfinite(value.std))
    std::snprintf(buf, sizeof buf, "%.1f +- %.1f", value.mean, value.std);
  else if (def.unit == Unit::Millimetre)  // one sequence: no spread measured
    std::snprintf(buf, sizeof buf, "%.1f", value.mean);
  else
    std::snprintf(buf, sizeof buf, "%.2f%%", 100.0 * value.mean);
  return buf;
}

}  // namespace layers::metrics
