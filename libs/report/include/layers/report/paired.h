// layers/report/paired.h -- paired comparisons of the report's rows on the
// accuracy axis: each learned row (an experiment whose model has trainable
// parameters) against each reference row (no parameters: static, skinned)
// and against the partner a study or `layers report --partner` names for
// it, over the sequences both evaluated on the same split of the same
// dataset with the same evaluation horizon. Per sequence,
// the row's error minus the other's (an experiment over seeds contributes
// its mean over seeds per sequence); the mean difference with its 95%
// interval (core/interval.h: paired Student t, sample standard deviation)
// and the wins and losses.
//
// Where a learned side is trained over several seeds, a second interval
// counts the seed-to-seed variance as well (docs/report.md, "Paired
// comparisons"): the squared standard error is the per-sequence one,
// sd^2 / n, plus, for each learned side with S >= 2 seeds, the sample
// variance over its seeds of the seed's mean error over the compared
// sequences divided by S, with Satterthwaite's degrees of freedom (rounded
// down for the t value). Reference rows have no seed variance. It is the
// interval read wherever it exists; a learned side with one seed beside
// one with several leaves it out (the seed variance of one seed is
// unknown). Each comparison also gets the two-sided p-value of the
// interval read, and the readings of one report are given both unadjusted
// and under Holm's rule over all its comparisons.
//
//   paired.csv  row, against, why (reference | partner), split, sequences,
//               mean_diff_mm, low_mm, high_mm, sd_mm, wins, losses, ties,
//               row_seeds, against_seeds (0: a reference row),
//               seeds_low_mm, seeds_high_mm, seeds_se_mm, seeds_df
//               (empty without the seed interval), interval (the one
//               read: sequences | sequences+seeds), p_value, reading,
//               holm_reading
#pragma once

#include <cstddef>
#include <map>
#include <string>
#include <vector>

#include "layers/core/interval.h"
#include "layers/report/run_results.h"

namespace layers::report {

struct PairedComparison {
  std::string row, against;
  std::string why;                             // "reference" or "partner"
  std::string split;                           // the split both rows are evaluated on
  MeanInterval difference;                     // row minus against, mm per sequence
  std::size_t wins = 0, losses = 0, ties = 0;  // sequences where the row's error is lower / higher / equal
  // Seeds of each side (0: a reference row, which has none).
  std::size_t row_seeds = 0, against_seeds = 0;
  // The interval with seed-to-seed variance (with_seeds false: not made).
  bool with_seeds = false;
  double seeds_se = 0, seeds_df = 0, seeds_half_width = 0;
  double seeds_low() const { return difference.mean - seeds_half_width; }
  double seeds_high() const { return difference.mean + seeds_half_width; }
  // The two-sided p-value of the interval read (NaN below two sequences).
  double p_value = 0;
  bool holm = false;  // rejected under Holm's rule over the report's comparisons
  // "lower" or "higher" when the interval read excludes 0, else "not separated".
  std::string reading() const;
  // The same, only where Holm's rule rejects; else "not separated".
  std::string holm_reading() const;
};

// `partners`: row name -> the row it is compared with besides the
// references (names are experiment names: a run's label, or for seed-<s>
// runs their experiment). A partner that is not among the runs is listed
// in `missing` ("<row>: partner <name> not in the report").
std::vector<PairedComparison> paired_comparisons(const std::vector<RunResults>& runs,
                                                 const std::map<std::string, std::string>& partners,
                                                 std::vector<std::string>* missing = nullptr);

std::string paired_csv(const std::vector<PairedComparison>& comparisons);

}  // namespace layers::report
