// layers/report/seeds.h -- experiments repeated over seeds (a study's
// <name>/seed-<s> run folders, run_results.h): each metric as mean and std
// over the seeds of the runs' overall means, beside the spread over
// sequences (the mean over the seeds of each run's std over sequences).
// Stds are sample stds (divided by n - 1), as over sequences.
//
//   seeds.csv  one row per experiment with two or more evaluated seeds:
//              experiment, model, split, seeds, the seed list, then per
//              metric its mean and std over seeds and its spread over
//              sequences, ms per frame, diverged sequences over all seeds
//              (the per-seed values are summary.csv's rows of those runs)
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "layers/report/run_results.h"

namespace layers::report {

struct SeedGroup {
  std::string experiment, model, split;
  std::vector<std::size_t> runs;     // indices of its evaluated runs, in report order
  std::vector<std::uint64_t> seeds;  // theirs, in the same order
  MetricStats over_seeds;            // mean, std over seeds; count = seeds with the value
  MetricStats over_sequences;        // mean = mean over seeds of each run's std over sequences
  double ms_per_frame = kAbsent;     // mean over seeds
  std::int64_t sequences = 0;        // per seed (the first seed's)
  std::int64_t diverged = 0;         // over all seeds
};

// The experiments with two or more evaluated seed-<s> runs, in the order
// of their first run.
std::vector<SeedGroup> seed_groups(const std::vector<RunResults>& runs);
// The group a run belongs to (index into `groups`), -1 for none.
int seed_group_of(const std::vector<SeedGroup>& groups, std::size_t run);

std::string seeds_csv(const std::vector<RunResults>& runs);

}  // namespace layers::report
