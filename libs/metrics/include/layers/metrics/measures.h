// layers/metrics/measures.h -- the measures behind the evaluation metrics
// (docs/metrics.md), per frame, plus mean +- std aggregation over
// sequences: the paper's definitions, and beside them our L-collision with
// its open-edge rule. registry.h declares the metrics built from them.
// Positions are metres; errors are reported in real-world millimetres
// (the paper's "mm" are at 10x scale, i.e. 10x these numbers). Torch-free.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "layers/geometry/mesh.h"
#include "layers/geometry/penetration.h"

namespace layers::metrics {

// Mean over vertices of |predicted - truth|, in mm. Row counts must match
// (layers::Error otherwise); a non-finite prediction gives a non-finite
// error, which rollouts use to detect divergence.
double euclidean_error_mm(const geometry::Points& predicted, const geometry::Points& truth);

// Share (0..1) of `points` behind `surface` (geometry::Surface: nearest
// vertex h, normal n, behind if (x - h) . n < 0). Non-finite points count
// as not behind. Zero points: layers::Error.
double behind_share(const geometry::Points& points, const geometry::Surface& surface);

// H-collision: share of garment vertices behind the body surface (the
// plain nearest-vertex test: the paper's definition; the body is closed).
double h_collision_rate(const geometry::Points& garment, const geometry::TriMesh& body);

// Two L-collisions, both reported by every evaluation (docs/metrics.md):
// the share of outer-garment vertices behind the inner garment surface
// (with several inner garments, geometry::concatenate them).
//
// l_collision_plain_rate: the paper's definition (LayersNet and its public
// code): an outer vertex counts when it lies behind the normal plane of its
// nearest inner vertex, wherever that vertex is. Use it to compare with the
// paper's figures.
double l_collision_plain_rate(const geometry::Points& outer, const geometry::TriMesh& inner);
// l_collision_rate: ours, the same nearest-vertex test with the open-edge
// rule: an outer vertex whose nearest inner vertex lies on an open edge of
// the inner garment (a hem, a cuff, a neckline) is beside that garment, not
// behind it, and does not count. (The plain test counts every jacket vertex
// hanging below a shorter inner garment: ~5% of the outer vertices in
// collision-free ground truth.)
double l_collision_rate(const geometry::Points& outer, const geometry::TriMesh& inner);
// Both at once (what every evaluation reports): one inner surface and one
// nearest-vertex query per outer vertex serve both rules.
struct LCollisionRates {
  double plain = 0, ours = 0;
};
LCollisionRates l_collision_rates(const geometry::Points& outer, const geometry::TriMesh& inner);

// Mean and sample standard deviation (divided by n - 1, as core/interval.h
// and numpy's std(ddof=1)) of per-sequence values; count = number of
// values; all zero when empty, std NaN for a single value (no spread is
// measured from one). Non-finite values propagate into mean and std.
struct MeanStd {
  double mean = 0.0;
  double std = 0.0;
  std::size_t count = 0;
};
MeanStd mean_std(const std::vector<double>& values);
// "mean +- std" with `decimals` digits after the point, e.g. "611.3 +- 544.3".
std::string format(const MeanStd& value, int decimals = 1);

// Per-frame values of one sequence, reduced to the sequence's value (the
// mean over its frames), then mean_std over sequences.
double sequence_mean(const std::vector<double>& per_frame);

}  // namespace layers::metrics
