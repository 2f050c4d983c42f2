// layers/report/run_results.h -- what a finished run folder holds, read
// back for reports: the evaluator's eval-<split>/metrics.json (format of
// libs/train/src/evaluator.cpp), `layers bench`'s bench.json
// (libs/train/src/bench.cpp), experiment.yaml (for data.dataset and
// model.name) and the path of eval-<split>/predictions.h5.
//
// Missing pieces are not errors: load_run records a readable message in
// RunResults::problems and leaves the piece empty. A file that exists but
// is malformed is reported the same way, with the InputError's text.
// The metrics are the registry's (layers/metrics/registry.h): each one
// registered is read where the file has it and is absent otherwise (an
// evaluation made before it was measured); one the file has but this
// build does not register is not read. Rates are shares 0..1, errors
// real-world mm, times ms; NaN = absent. `selection` (what chose the
// checkpoint) reads as "unknown" when absent.
//
// A folder named seed-<s> is one repetition of a study experiment repeated
// over seeds (<study>/<name>/seed-<s>): it is labelled "<name>/seed-<s>",
// and seeds.h groups such runs by <name>.
#pragma once

#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace layers::report {

constexpr double kAbsent = std::numeric_limits<double>::quiet_NaN();

struct Stat {
  double mean = kAbsent, std = kAbsent;
  std::int64_t count = 0;  // sequences the value is over; 0 = absent
};

// {mean, std, count} of each metric, by registry key.
struct MetricStats {
  std::map<std::string, Stat> by_key;
  Stat get(const std::string& key) const;  // absent: count 0, NaN
};

// One row of metrics.json's by_step: means over the sequences still rolling
// out at that step (step 1 = the first predicted frame).
struct StepMetrics {
  std::int64_t step = 0;
  std::map<std::string, double> by_key;
  std::int64_t sequences = 0;
  double get(const std::string& key) const;  // kAbsent when absent
};

struct SequenceMetrics {
  std::string id;
  double error_mm = kAbsent;
  std::int64_t diverged_at = -1;  // absolute frame, -1 when stable
  std::string diverge_reason;
};

// What chose the evaluated checkpoint (metrics.json's `selection`,
// libs/train evaluator.h); "unknown" for an evaluation made before it.
struct SelectionRecord {
  std::string checkpoint = "unknown";  // best, last
  std::string chosen_on = "unknown";   // the split whose validation error chose it; none: nothing chosen
  std::string evaluated_on;            // the evaluated split (metrics.json's split when absent)
  std::int64_t chosen_epoch = 0;       // 1-based; 0 = none or unknown
  std::int64_t epochs = 0;             // train.epochs; 0 = unknown
  std::string metric;                  // what compared the epochs ("" = none or unknown)
  // The validation error (mm) of the chosen epoch: the run folder's
  // selection.json best_val_error_mm when the evaluated checkpoint is the
  // best one; kAbsent otherwise. What a variant is picked by.
  double val_error_mm = kAbsent;
};

struct EvalResults {
  std::string file;  // the metrics.json read
  std::string model, split, dataset, checkpoint;
  std::int64_t sequences = 0, frames = 0, diverged = 0, parameters = 0, horizon = 0;
  double ms_per_frame = kAbsent, diverge_mm = kAbsent;
  MetricStats overall;
  std::map<std::string, double> truth;                        // the ground truth's, by metric key
  double truth_of(const std::string& key) const;              // kAbsent when absent
  std::vector<std::pair<std::string, MetricStats>> per_type;  // garment type -> stats
  std::vector<StepMetrics> by_step;
  std::vector<SequenceMetrics> per_sequence;
  std::string predictions;  // eval-<split>/predictions.h5 when it exists
  SelectionRecord selection;

  // The rollout step of the earliest divergence over all sequences, -1 when
  // none diverged. Rollouts start from the ground truth at frames 0 and 1,
  // so absolute frame f is step f - 1.
  std::int64_t first_divergence_step() const;
};

struct BenchPoint {
  int level = 0;
  bool far_body = false;
  std::int64_t garment_vertices = 0, body_vertices = 0;
  std::map<std::string, double> counters;
  double ms_per_frame = kAbsent, train_ms_per_frame = kAbsent;
};

struct BenchResults {
  std::string file, model, sequence;
  std::int64_t parameters = 0;
  int threads = 0;
  std::vector<BenchPoint> rows;
};

// Validation error (mm) at the end of each training epoch against the
// training windows seen by then (selection.json; NaN where unknown).
// A run trained before the trainer kept the errors of every epoch has only
// its chosen epoch's (only_best: NaN at the other epochs). The protocol
// is known for runs whose selection.json records it (else horizon 0).
struct LearningCurve {
  std::vector<double> val_error_mm, windows_seen;
  bool only_best = false;
  std::string split;            // the split validated on ("" unknown)
  std::int64_t horizon = 0;     // rollout frames (0 unknown)
  std::int64_t sequences = -1;  // first N sequences; 0 every one; -1 unknown
};

struct RunResults {
  std::string dir;                  // the run folder as given
  std::string name;                 // its last path component: the run's label everywhere
  std::string model;                // metrics.json's model, else experiment.yaml's model.name
  std::string dataset;              // experiment.yaml's data.dataset, else metrics.json's dataset
  std::string test_split = "test";  // experiment.yaml's data.test_split (default "test")
  std::string experiment;           // the folder's name; for a seed-<s> folder, its parent's name
  bool repeated = false;            // a seed-<s> folder (name "<experiment>/seed-<s>")
  std::uint64_t seed = 0;           // its <s>
  // experiment.yaml without run.seed, run.output and data.dataset ("" when
  // unreadable): seed runs of one experiment kept in different folders
  // (parts of a study run in several sittings) share it.
  std::string settings;
  std::optional<EvalResults> eval;
  // Its evaluation on the split its curve was validated on (eval-val),
  // read besides `eval` when that is another split: a reference row's
  // value on the learning curves' measure.
  std::optional<EvalResults> val_eval;
  std::optional<BenchResults> bench;
  LearningCurve curve;                // empty without selection.json or its per-epoch record
  std::vector<std::string> problems;  // readable messages about missing or bad pieces (without the folder)
};

// A reference row (an evaluation without trained parameters: static,
// skinned) measured on the learning curves' validation protocol: the same
// split and rollout frames, over every sequence the curves validated on
// (the curves' first N when N covers them all). The protocol is the one
// every curve with a recorded protocol shares; `notes` says why a
// reference row or the whole set has no level.
struct ReferenceLevel {
  std::string name;
  double error_mm = kAbsent;
};
std::vector<ReferenceLevel> curve_references(const std::vector<RunResults>& runs, std::vector<std::string>* notes);

// Parsers of the two JSON files (`file` names the source in errors).
// Throw InputError for malformed JSON, a missing required field
// (metrics.json: model, overall.error_mm; bench.json: model, rows) or a
// field of the wrong type.
EvalResults parse_metrics(const std::string& json_text, const std::string& file);
BenchResults parse_bench(const std::string& json_text, const std::string& file);

// Why the run's figures cannot be trusted as a held-out result, "" when
// they can or nothing is known: its checkpoint was chosen on the test split
// (RunResults::test_split) or on the split it is evaluated on.
std::string selection_flag(const RunResults& run);

// What a caption's figures are over: "the test sequences" when every run
// with an evaluation is on one split (here test), "each run's evaluated
// sequences (val or test)" when they differ (splits in first-seen order),
// "the evaluated sequences" when no run names its split.
std::string evaluated_sequences(const std::vector<RunResults>& runs);
// The same over the runs a chart plots (indices into `runs`).
std::string evaluated_sequences(const std::vector<RunResults>& runs, const std::vector<std::size_t>& plotted);

// The run folders with each folder that holds no run of its own but
// seed-<s> folders (a study experiment repeated over seeds) replaced by
// those, in seed order.
std::vector<std::string> expand_seed_folders(const std::vector<std::string>& dirs);

// Reads a run folder. `split` picks eval-<split>/; empty: eval-test when
// present, else the first eval-* folder in name order. Never throws for
// missing or malformed files (see RunResults::problems).
RunResults load_run(const std::string& dir, const std::string& split = "");

}  // namespace layers::report
