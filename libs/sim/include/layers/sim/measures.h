// layers/sim/measures.h -- validation measures of a simulated frame and of
// a whole sequence (docs/metrics.md "Generator validation measures").
//
//  - H-penetration: share of garment vertices behind the body surface (for
//    the nearest body vertex h with area-weighted normal n: (x - h) . n < 0).
//  - L-penetration: share of outer-garment vertices behind the inner layer
//    (all inner garments together as one surface): the nearest inner
//    vertex, the closest point among its faces, a negative signed offset
//    from that point of at most `l_reach`; a vertex beside an open
//    boundary of the inner garment (past its hem, cuff or neckline, rather
//    than over or under its surface) is not behind it, and neither is one
//    farther than `l_reach` from the inner layer, where the nearest inner
//    point says nothing about being inside it (a jacket sleeve over a bare
//    forearm finds the armhole of a sleeveless dress; docs/sim.md 6).
//  - maximum edge stretch: max over edges of |l| / l0 - 1 (compression does
//    not count).
//  - non-finite count: NaN or infinite coordinates.
//  - H- and L-crossing (exact, geometry/intersect.h): share of garment
//    vertices on garment faces that pass through a body face, and share of
//    outer vertices on outer faces that pass through an inner face, with
//    the number of crossing face pairs. No heuristic: contact without
//    crossing never counts, a crossing is never missed.
//  - cloth crossings (exact): crossing face pairs between any two garments
//    (inner and outer, and garments of the same layer) and within each
//    garment that has self-contact; the collision pass keeps them at zero
//    (docs/sim.md "Contact").
//  - body self-crossing: share of body faces that pass through another
//    body face (geometry::self_crossings; a posed arm sunk into the torso).
//  - pinch zones (geometry/pinch.h): share of body faces where two parts
//    of the body cross or come closer than ValidationConfig::pinch_distance
//    (no room for the cloth stack between them). The H-crossing is split
//    into the part inside pinch zones (only crossings with pinch-zone body
//    faces) and the part clear of them (all other body faces); the clear
//    part has its own threshold (max_h_crossing_clear).
// A sequence passes when the mean H- and L-penetration over its frames,
// the largest H- and L-crossing and cloth crossings of any frame and its
// maximum stretch stay under the ValidationConfig thresholds and no value
// is non-finite.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "layers/geometry/mesh.h"
#include "layers/geometry/penetration.h"
#include "layers/sim/config.h"

namespace layers::sim {

class Solver;

// Share of the rows of `points` behind `surface` (0 when there are none).
double penetration_rate(const geometry::Points& points, const geometry::Surface& surface);
// Garment vertices (all garments together) behind the body.
double h_penetration_rate(const std::vector<geometry::Points>& garments, const geometry::TriMesh& body);
// Outer vertices behind the inner garments (one surface, with the
// open-boundary and reach rules above). Given the body, a vertex counts
// only if the inner layer also covers it along the body's outward normal
// (the first inner face on that ray within `reach` is crossed from its
// back), which keeps folds of the inner garment from counting.
double l_penetration_rate(const std::vector<geometry::Points>& outer, const std::vector<geometry::TriMesh>& inner,
                          double reach = std::numeric_limits<double>::infinity(),
                          const geometry::Surface* body = nullptr);
// max(0, max over edges of |x_i - x_j| / l0 - 1); edges and rest lengths as
// a Cloth gives them.
double max_edge_stretch(const geometry::Points& positions, const geometry::Edges& edges,
                        const Eigen::VectorXd& rest_lengths);
std::int64_t count_nonfinite(const geometry::Points& points);

struct MeasuredGarment;
// Crossing face pairs between any two of `garments` and within each that
// has self-contact (positions as they are; non-finite faces cross nothing).
std::int64_t cloth_crossings(const std::vector<MeasuredGarment>& garments);

struct FrameMeasures {
  double h_penetration = 0;  // NaN when not measurable (non-finite positions)
  double l_penetration = 0;  // 0 with a single layer; NaN when not measurable
  double max_stretch = 0;
  std::int64_t nonfinite = 0;
  double h_crossing = 0;  // NaN when not measurable
  double l_crossing = 0;  // 0 with a single layer; NaN when not measurable
  std::int64_t h_crossing_pairs = 0, l_crossing_pairs = 0;
  std::int64_t cloth_crossing_pairs = 0;  // any two garments, and self where the garment has self-contact
  double body_self_crossing = 0;          // share of body faces; NaN when not measured
  double body_pinch = 0;        // share of the body faces under the garments in pinch zones; NaN when not measured
  double h_crossing_clear = 0;  // H-crossing outside pinch zones; NaN when not measured
  double h_crossing_pinch = 0;  // H-crossing inside pinch zones; NaN when not measured
};

// One garment as measured: its positions, its edges with rest lengths and
// whether it is an outer garment (dataset layer 1) or an inner one.
struct MeasuredGarment {
  geometry::Points positions;
  geometry::Faces faces;
  geometry::Edges edges;
  Eigen::VectorXd rest_lengths;
  bool outer = false;
  bool self_contact = false;  // its own crossings count among the cloth crossings
};

// `body_self`: also measure the body's own crossings, its pinch zones
// (vertices within `pinch_distance` of a body part; 0: crossings only) and
// the H-crossing inside and clear of them (about 60 ms for a 27k-face
// body; NaN when not asked).
FrameMeasures measure_frame(const geometry::TriMesh& body, const std::vector<MeasuredGarment>& garments,
                            double l_reach = ValidationConfig{}.l_reach, bool body_self = true,
                            double pinch_distance = ValidationConfig{}.pinch_distance);
// The solver's current frame: its body and cloths; the cloths of the
// highest layer are the outer garments, all others inner; the L reach and
// pinch distance are the solver's config().validation's. The generator's
// per-frame check: body self-crossings and pinch zones only where
// validation.max_h_crossing_clear asks for them (below 1); `layers validate
// --physics` reports them from the stored frames.
FrameMeasures measure_frame(const Solver& solver);

// A broken validation rule: its name (the ValidationConfig setting without
// `max_`: non_finite, h_crossing, h_crossing_clear, l_crossing,
// cloth_crossings, stretch; for a sequence also h_penetration,
// l_penetration) and one sentence saying by how much.
struct Violation {
  const char* rule;
  std::string sentence;
};

// The rules every single frame must keep (all but the two means over
// frames): no non-finite coordinate, crossings and stretch within their
// limits. Empty when the frame keeps them. The generator's clean windows
// (docs/sim.md) end before the first frame that breaks one.
std::vector<Violation> frame_violations(const FrameMeasures& frame, const ValidationConfig& limits);

// Running totals over the frames of a sequence.
class SequenceMeasures {
 public:
  void add(const FrameMeasures& frame);
  int frames() const { return frames_; }
  int measured() const { return measured_; }  // frames whose measures are all finite
  double mean_h_penetration() const;          // over measured frames (0 when none)
  double mean_l_penetration() const;
  double mean_h_crossing() const;
  double mean_l_crossing() const;
  double max_h_crossing() const { return max_h_crossing_; }  // worst frame
  double max_l_crossing() const { return max_l_crossing_; }
  // Over the frames that measured them (NaN when none did).
  double mean_body_self_crossing() const;
  double mean_h_crossing_clear() const;
  double max_h_crossing_clear() const { return max_h_crossing_clear_; }
  double mean_body_pinch() const;
  double mean_h_crossing_pinch() const;
  double max_h_crossing_pinch() const { return max_h_crossing_pinch_; }
  double max_stretch() const { return max_stretch_; }
  std::int64_t max_cloth_crossings() const { return max_cloth_crossings_; }  // worst frame's pairs
  std::int64_t nonfinite() const { return nonfinite_; }
  // Empty when the sequence passes; else one sentence per violated threshold
  // (e.g. "mean H-penetration 0.81% exceeds 0.50%").
  std::vector<std::string> violations(const ValidationConfig& thresholds) const;
  // The same with each rule's name (Violation), in the same order.
  std::vector<Violation> broken(const ValidationConfig& thresholds) const;

 private:
  int frames_ = 0, measured_ = 0;
  double sum_h_ = 0, sum_l_ = 0, max_stretch_ = 0;
  double sum_hx_ = 0, sum_lx_ = 0, max_h_crossing_ = 0, max_l_crossing_ = 0;
  int measured_self_ = 0;
  double sum_self_ = 0, sum_hx_clear_ = 0, max_h_crossing_clear_ = 0;
  double sum_pinch_ = 0, sum_hx_pinch_ = 0, max_h_crossing_pinch_ = 0;
  std::int64_t nonfinite_ = 0, max_cloth_crossings_ = 0;
};

}  // namespace layers::sim
