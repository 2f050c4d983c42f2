// layers/body/self_intersection.h -- body self-intersection per frame.
//
// The skin is split into five parts by skinning weights (torso with head,
// hips and clavicles; each arm; each leg). A vertex belongs to a part when
// at least 99% of its weight is on that part's bones; the blend zones
// between parts (armpits, groin, shoulders) deform into each other by
// construction and are not tested. Per frame, vertices of a limb are
// tested against the surfaces of the other parts it can hit (arm -> torso,
// legs, other arm; leg -> torso, other leg) with the nearest-vertex sign
// test of layers::geometry: a vertex x whose nearest surface vertex h
// (normal n) is closer than `max_distance` and has (x - h) . n < 0 lies
// inside, by depth -(x - h) . n. Bounding boxes skip pairs that cannot
// touch. Depths are attributed to the limb that should move (an arm, or
// both legs for leg/leg and leg/torso contact).
//
// That test is blind where it matters most for cloth: in the blend zones
// (a hand sunk into the buttocks, an armpit folding into the chest, the
// inner thighs pressing through each other at the groin) and deeper than
// `max_distance`. With `exact` on, check() also counts the exact crossings
// (layers::geometry::crossings, one face tree per region) between faces of different
// regions: every face is labelled by the part that carries at least half
// of its skinning weight (torso otherwise, blend zones included), and a
// crossing between two regions is attributed as above. Crossings inside
// one region (fingers, toes, elbow and knee pits, the groin's own folds)
// are not counted: no limb turn clears them.
//
// With a gap (IntersectionOptions::gap > 0, the paper's 4 mm) the verdict
// asks for room instead of allowing depth: a limb vertex closer than the
// gap in front of another part's surface offends, wherever the two parts
// are not neighbours -- everywhere for arm/arm and arm/leg, and beyond
// 40% of the upper arm from the shoulder (30% of the thigh from the hip)
// for a limb against the torso and for the thighs against each other.
// Nearer the joint, where the limb lies against its neighbour by
// construction and no turn about the joint opens it, the depth tolerance
// still applies.
//
// Per frame it also measures the room a limb leaves the cloth (arm to
// torso, thigh to thigh; the motion's arm and thigh room).
#pragma once

#include <array>
#include <limits>
#include <string>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/geometry/mesh.h"

namespace layers::body {

enum class BodyPart { torso = 0, left_arm = 1, right_arm = 2, left_leg = 3, right_leg = 4 };
constexpr int kNumBodyParts = 5;
const char* body_part_name(BodyPart part);

struct IntersectionOptions {
  double tolerance = 0.004;    // m: deeper than this counts as intersecting
  double gap = 0.0;            // m: room non-neighbouring parts keep (0 = contact allowed; see above)
  double max_distance = 0.06;  // m: farther from the nearest surface vertex is not tested
  bool exact = true;           // also count exact crossings between regions
};

struct FrameIntersection {
  double depth = 0.0;                  // deepest penetration found (m)
  std::array<double, 4> limb_depth{};  // left arm, right arm, left leg, right leg
  // How far the worst tested vertex is from what the options ask (m; > 0
  // offends): gap - offset where a gap is asked, depth - tolerance
  // elsewhere; -infinity when no part is near another. Per limb as above.
  double shortfall = -std::numeric_limits<double>::infinity();
  std::array<double, 4> limb_shortfall{
      -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
      -std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()};
  int vertices = 0;  // vertices that offend
  // Exact crossings between regions (face pairs), all and per limb.
  int crossings = 0;
  std::array<int, 4> limb_crossings{};
  // Per arm (left, right): the smallest offset of its core vertices
  // beyond 40% of the upper arm from the shoulder in front of the torso's
  // surface (m; nearest-vertex test, torso vertices next to a blend zone
  // left out), infinity when none is within
  // `max_distance`. The room the arm leaves the cloth between it and the
  // torso (the motion's arm room, body_sequence.h).
  std::array<double, 2> arm_gap{std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  // Between the legs: the smallest offset of the left leg's core vertices
  // beyond 30% of the thigh from the hip in front of the right leg's
  // surface (m; same test, the groin's blend zone left out), infinity when
  // none is within `max_distance`. The room the thighs leave the cloth of
  // two trouser legs between them (the motion's thigh room).
  double thigh_gap = std::numeric_limits<double>::infinity();
  // The verdict that drops frames: a vertex deeper than the tolerance, or
  // closer than the gap where one is asked.
  bool offends() const { return shortfall > 0.0; }
  // What the repair clears where its limits allow: the verdict above and
  // every exact crossing counted.
  bool needs_repair() const { return offends() || crossings > 0; }
};

// Keeps a reference to `body`, which must outlive it.
class SelfIntersection {
 public:
  explicit SelfIntersection(const Body& body, IntersectionOptions options = {});

  // `posed`: the skin vertices of one frame (same order as body.rest).
  FrameIntersection check(const geometry::Points& posed) const;
  // The same, counting only the crossings attributed to the limbs marked
  // in `crossings` (left arm, right arm, left leg, right leg): the region
  // pairs no marked limb moves for are not tested.
  FrameIntersection check(const geometry::Points& posed, const std::array<bool, 4>& crossings) const;

  const IntersectionOptions& options() const { return options_; }
  // Per skin vertex its part, or -1 in a blend zone.
  const std::vector<int>& part() const { return part_; }

 private:
  void count_crossings(const geometry::Points& posed, const std::array<bool, 4>& wanted, FrameIntersection& out) const;

  const Body& body_;
  IntersectionOptions options_;
  std::vector<int> part_;
  std::array<std::vector<int>, kNumBodyParts> members_;  // core vertices per part
  std::vector<char> near_blend_;                         // core vertex next to a blend zone
  std::vector<char> gap_vertex_;                         // limb vertex whose arm_gap / thigh_gap counts
  std::vector<signed char> region_;                      // per face: the part carrying >= 1/2 of its weight
  std::array<std::vector<int>, kNumBodyParts> region_faces_;
};

}  // namespace layers::body
