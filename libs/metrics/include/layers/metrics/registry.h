// layers/metrics/registry.h -- every evaluation metric, declared once:
// its name, unit, scope, what a diverged frame counts as, how it reduces
// over frames, which direction is better, the rule of docs/metrics.md it
// implements, its words for tables and charts, and the function that
// measures one frame. The evaluator (libs/train), metrics.json,
// sequences.csv, `layers eval` and `layers report` (its tables, seed
// tables and charts) iterate this list; none spells a metric's name
// except error_mm, the accuracy axis (kError).
//
// How values aggregate, for every metric:
//   vertices   inside `compute`: a mean over vertices (mm) or a share of
//              vertices (0..1), for the whole scene and per garment;
//   frames     a sequence's value is the mean (Reduce::Mean) or maximum
//              (Reduce::Max) of its frames' finite values; frames after a
//              divergence count as the bound (Diverged::Bound) or are left
//              out (Diverged::LeftOut);
//   sequences  mean +- std over the sequences with a finite value (per
//              garment type: over the garments of that type);
//   steps      by rollout step: mean over the sequences' finite values;
//   seeds      mean +- std over the seeds of each seed's mean.
// Metrics of Scope::OuterLayer give every outer garment the scene's value
// and inner garments none (NaN).
#pragma once

#include <cstddef>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "layers/metrics/frame_scene.h"

namespace layers::metrics {

// The accuracy metric: divergence is judged on it, reports chart speed
// against it.
inline constexpr const char* kError = "error_mm";

enum class Unit { Millimetre, Share };  // Share: 0..1, shown as a percentage
enum class Scope { EveryGarment, OuterLayer };
enum class Diverged { Bound, LeftOut };
enum class Reduce { Mean, Max };
enum class Better { Lower, Higher };

// One frame's value: over the scene's vertices in scope, and per garment
// (size() of the scene; NaN where the metric does not measure a garment).
// `scene` NaN: not measured in this frame (e.g. no inner + outer pair).
struct FrameValue {
  double scene = 0;
  std::vector<double> garments;
};

struct MetricDef {
  std::string key;          // metrics.json, CSV and chart name: lower_snake_case
  std::string label;        // table heading, e.g. "H-collision"
  std::string axis;         // chart axis, e.g. "garment vertices behind the body"
  std::string description;  // one sentence for captions and `layers eval`
  std::string rule;         // the section of docs/metrics.md it implements
  Unit unit = Unit::Share;
  Scope scope = Scope::EveryGarment;
  Diverged diverged = Diverged::LeftOut;
  Reduce frames = Reduce::Mean;
  Better better = Better::Lower;
  bool truth = false;  // also measured on the ground truth, reported beside
  std::function<FrameValue(const FrameScene&)> compute;
};

// The registered metrics, in order: the built-in ones (error_mm,
// h_collision, l_collision, l_collision_plain, h_crossing, l_crossing),
// then any added.
const std::vector<MetricDef>& registered();
// Index of `key` in registered(); layers::Error when none.
std::size_t index_of(const std::string& key);
const MetricDef& metric(const std::string& key);

// Adds a metric at the end (layers::Error for a bad or taken key, a
// missing compute, or Diverged::Bound on a metric not in mm). Registration
// is for start-up and tests: an evaluation works on a copy of the list
// taken when it starts, and refuses rollouts measured with another list.
void add(MetricDef def);
// Removes an added metric (the built-in ones stay).
void remove(const std::string& key);

// A metric registered for the lifetime of this object.
class ScopedMetric {
 public:
  explicit ScopedMetric(MetricDef def);
  ~ScopedMetric();
  ScopedMetric(const ScopedMetric&) = delete;
  ScopedMetric& operator=(const ScopedMetric&) = delete;

 private:
  std::string key_;
};

// The usual frame value of a per-garment measure: each garment's value,
// and the scene's as their mean weighted by vertex count (`if_empty` for a
// scene without vertices).
FrameValue vertex_weighted(const FrameScene& s, const std::function<double(std::size_t garment)>& per_garment,
                           double if_empty = std::numeric_limits<double>::quiet_NaN());

// A sequence's value from its frames' values (the frames rule above).
double reduce_frames(const MetricDef& def, const std::vector<double>& values);
// Mean of the finite values, NaN when none.
double finite_mean(const std::vector<double>& values);
// mean_std over the finite values.
MeanStd finite_mean_std(const std::vector<double>& values);

// Text of a value in the metric's unit: "12.3 +- 4.5" (mm, mean +- std) or
// "1.25%" (shares, the mean); "-" when there is no value (count 0).
std::string format_value(const MetricDef& def, const MeanStd& value);

}  // namespace layers::metrics
