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
//   paired.csv  row, against, why (reference | partner), split, sequences,
//               mean_diff_mm, low_mm, high_mm, sd_mm, wins, losses, ties
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
  // "lower" or "higher" when the interval excludes 0, else "not separated".
  std::string reading() const;
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
