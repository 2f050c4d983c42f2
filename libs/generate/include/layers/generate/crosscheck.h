// layers/generate/crosscheck.h -- the measures and the markdown table of
// `layers crosscheck` (docs/sim.md "Cross-check against Blender"): one
// column per simulation of the same scene (our stored ground truth, each
// Blender setup), measured with one code path for all of them.
//
// Rows (frames 1 .. n-1; frame 0 is the shared start and is left out):
//  - ms per frame, as given by the caller (NaN: "n/a");
//  - edge stretch max(0, |l| / l0 - 1) against the stored rest shape, p99
//    over every edge of every garment and frame, and its maximum;
//  - H: share of garment vertices behind the nearest body vertex's normal
//    plane (geometry::Surface), mean over frames;
//  - L: share of outer-garment vertices behind the nearest inner vertex's
//    normal plane (all inner garments as one surface; plain test, no
//    open-edge rule) and within 1 cm of that vertex; within 3 cm; any
//    distance; means over frames;
//  - the generator's own measures (sim::measure_frame): mean H, mean L
//    (its rule: covered test, open-edge rule, 3 cm reach), max stretch;
//  - exact crossings (geometry/intersect.h, through sim::measure_frame):
//    share of garment vertices on garment faces that pass through a body
//    face, and of outer vertices on outer faces that pass through an inner
//    face; mean over frames and worst frame.
// Below the table, the generator's measures of the stored frame 0.
// Non-finite positions make a frame unmeasurable; they are counted.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/generate/quantile.h"
#include "layers/sim/measures.h"

namespace layers::generate {

// The labels of our two columns: the stored ground truth, and the scene
// simulated again by our solver (timed).
inline constexpr const char* kOursStored = "ours (stored)";
inline constexpr const char* kOursAgain = "ours (simulated again)";

// One simulation of a sequence's garments: positions [T,V,3] per garment
// (the sequence's garment order and vertex order), T >= frames measured.
struct CrosscheckRun {
  std::string label;                                               // column header
  double ms_per_frame = std::numeric_limits<double>::quiet_NaN();  // NaN: n/a
  std::vector<std::vector<float>> garments;
};

struct CrosscheckColumn {
  std::string label;
  double ms_per_frame = std::numeric_limits<double>::quiet_NaN();
  std::int64_t frames = 0;     // frames measured (1 .. n-1)
  std::int64_t nonfinite = 0;  // non-finite coordinates seen
  double stretch_p99 = 0, stretch_max = 0;
  double h = 0;  // share, 0..1
  double l_1cm = 0, l_3cm = 0, l_all = 0;
  double gen_h = 0, gen_l = 0, gen_stretch_max = 0;
  double h_crossing = 0, h_crossing_max = 0;  // exact garment-body crossings
  double l_crossing = 0, l_crossing_max = 0;  // exact layer crossings
};

// The shares and quantiles of one run over frames [1, n_frames) of `seq`
// (its body, faces, rest shapes and layers; its garment positions are
// ignored). InputError when a run's garments do not match the sequence's
// or hold fewer than n_frames frames.
CrosscheckColumn measure_crosscheck(const data::SequenceData& seq, const CrosscheckRun& run);

// Our solver timed on the scene: sequence `sequence_id` of the dataset
// folder `dataset_dir` simulated again from the generator config its
// dataset.yaml records (drape and blend untimed), frames 0..frames-1
// recorded; ms_per_frame is the CPU time of frames 1..n-1 on this thread.
// The positions equal the stored ones when the solver has not changed
// since the dataset was made. InputError when the manifest or its
// generator config is missing or the scene cannot be made.
CrosscheckRun resimulate_ours(const std::string& dataset_dir, const std::string& sequence_id, std::int64_t frames);

// The generator's measures (with the exact crossings) of the stored frame
// 0, where every run starts.
sim::FrameMeasures measure_start(const data::SequenceData& seq);

// Markdown: a header line naming the scene, then one row per measure and
// one column per run; with `start`, a line on frame 0 below the table.
std::string crosscheck_table(const std::string& title, const std::vector<CrosscheckColumn>& columns,
                             const sim::FrameMeasures* start = nullptr);

}  // namespace layers::generate
