// layers/generate/physics_summary.h -- what `layers validate --physics`
// prints below its per-sequence table: the spread of each per-sequence
// measure over the sequences (min, p10, median, p90, max) and how many
// frames and sequences meet a crossing target (issue target: under 0.1%
// H- and L-crossing in every frame; docs/sim.md, section 6).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "layers/sim/measures.h"

namespace layers::generate {

// The spread of one measure over sequences; NaN values are left out
// (count says how many were kept; all fields 0 when none).
struct Spread {
  int count = 0;
  double min = 0, p10 = 0, median = 0, p90 = 0, max = 0;
};
Spread spread_of(const std::vector<double>& values);

class PhysicsSummary {
 public:
  // `target`: the crossing share (0..1) a frame must not exceed.
  explicit PhysicsSummary(double target = 0.001) : target_(target) {}

  // One frame of the current sequence. A frame whose crossing is not
  // measurable (NaN) does not meet the target.
  void add_frame(const sim::FrameMeasures& frame);
  // Ends the current sequence with its per-sequence values, as (column
  // name, share 0..1; NaN: not measurable) in the same order for every
  // sequence. Error, with nothing recorded, when the columns differ from
  // the first sequence's.
  void end_sequence(const std::vector<std::pair<std::string, double>>& columns);

  std::int64_t frames() const { return frames_; }
  std::int64_t frames_h_within() const { return h_within_; }
  std::int64_t frames_l_within() const { return l_within_; }
  std::int64_t frames_both_within() const { return both_within_; }
  int sequences() const { return sequences_; }
  int sequences_within() const { return sequences_within_; }  // both within in every frame
  Spread spread(const std::string& column) const;             // Error for an unknown column

  // The lines printed: a header, one line per column (as percentages),
  // and the target's counts.
  std::string text() const;

 private:
  double target_;
  std::int64_t frames_ = 0, h_within_ = 0, l_within_ = 0, both_within_ = 0;
  int sequences_ = 0, sequences_within_ = 0;
  bool current_within_ = true;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> values_;  // per column, per sequence
};

}  // namespace layers::generate
