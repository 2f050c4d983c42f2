// layers/data/stats.h -- normalisation statistics (stats.h5).
//
// Mean and standard deviation per x/y/z component of garment and body
// vertex positions, velocities and accelerations, all relative to the body
// root of the same frame (p_rel(t) = p(t) - root(t)); velocity and
// acceleration are per-frame differences (dt = 1 frame):
//   v(t) = p_rel(t) - p_rel(t-1),  a(t) = v(t) - v(t-1).
// Computed from one split (train) only, streaming over frame blocks with
// double accumulators (pairwise mean/M2 merging). Standard deviations are
// population ones, floored at std_floor so normalising never divides by 0.
//
// stats.h5 layout (all float64):
//   /                         attrs format="layers-stats", format_version=1,
//                             split, n_sequences, n_frames, std_floor
//   /garment/position/mean [3], /garment/position/std [3], attr count
//   /garment/velocity/...,  /garment/acceleration/...
//   /body/position/..., /body/velocity/..., /body/acceleration/...
// `count` is the number of xyz samples that went into the moments.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace layers::data {

class Dataset;

struct Moments {
  std::array<double, 3> mean{0, 0, 0};
  std::array<double, 3> std{1, 1, 1};
  std::int64_t count = 0;
};

struct NormStats {
  Moments garment_position, garment_velocity, garment_acceleration;
  Moments body_position, body_velocity, body_acceleration;
  std::string split = "train";
  std::int64_t n_sequences = 0, n_frames = 0;
  double std_floor = 1e-6;
};

struct StatsOptions {
  std::string split = "train";
  double std_floor = 1e-6;
};

// Calls f(path, moments) for the six quantities of `stats`, with their
// stats.h5 group paths ("garment/position", ..., "body/acceleration").
template <class Stats, class F>
void for_each_quantity(Stats& stats, F&& f) {
  f("garment/position", stats.garment_position);
  f("garment/velocity", stats.garment_velocity);
  f("garment/acceleration", stats.garment_acceleration);
  f("body/position", stats.body_position);
  f("body/velocity", stats.body_velocity);
  f("body/acceleration", stats.body_acceleration);
}

// Throws InputError if the split is missing or empty, a sequence has
// fewer than 3 frames worth of data overall, or a value is not finite.
NormStats compute_stats(const Dataset& dataset, const StatsOptions& options = {});
void write_stats(const std::string& path, const NormStats& stats);  // atomic
NormStats read_stats(const std::string& path);
// read_stats, and when the file is a dataset's stats.h5 (beside a
// dataset.yaml), its values checked against the recorded stats_hash as
// every dataset reader checks them (InputError when they differ or, unless
// allow_unhashed, when none is recorded).
NormStats read_stats_verified(const std::string& path, bool allow_unhashed = false);
// The content hash of the statistics (16 hex digits): what dataset.yaml's
// stats_hash records and the readers verify (integrity.h).
std::string stats_content_hash(const NormStats& stats);
// Writes <folder>/stats.h5 and records its hash in the folder's
// dataset.yaml; how the generator and `layers stats` store a dataset's
// statistics.
void write_dataset_stats(const std::string& folder, const NormStats& stats);

}  // namespace layers::data
