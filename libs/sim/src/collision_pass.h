// collision_pass.h (internal) -- the continuous-collision safety pass that
// ends every substep, after every position edit (docs/sim.md "Contact").
//
// Every vertex moves on a straight line from where it was at the start of
// the substep (Cloth::State::x_start; the body's pose of the previous
// substep) to where the substep left it. The pass finds every
// vertex-triangle and edge-edge pair whose features come closer than the
// pass's gap during that motion (additive CCD, ccd.h), between:
//  - any two different cloths (inner and outer layers, and garments of the
//    same layer such as a t-shirt and trousers);
//  - a cloth and itself, for cloths with self-contact (pairs that share a
//    vertex left out);
//  - a cloth and the body, whose triangles sweep with it; pairs already
//    crossed at the start of the substep (a cloth vertex behind a body
//    face's plane; the cloth on the inner side of a body vertex or edge,
//    by the body's vertex normals) are left to the proximity passes.
// Broad phase: the shared candidate list (contact_candidates.h), which
// holds every pair that can come within the gap while the cloth stays
// within its bounds and the body on its frame's sweep; each detection
// tests the listed pairs whose swept boxes (grown by half the gap; the
// body's over the frame) overlap. Repeat detections test only the pairs
// with a feature moved since the last one.
//
// Response, in rounds (at most `rounds`): each pair found is pushed apart
// along the direction between its closest points at the time CCD stopped,
// until the end positions are 2 x gap apart along it, split by inverse mass
// (the body does not move), Gauss-Seidel in the order found. Then impact
// zones: the cloth vertices of cloth-cloth pairs still failing, merged
// with the zones they touch (union-find), each moved rigidly with its
// mass's mean motion and spin, up to kZoneRounds times. Then the
// fail-safe: every cloth vertex of a cloth-cloth pair still failing is put
// back where it was at the start of the substep (its motion for this
// substep undone), until no failing cloth-cloth pair has a moving vertex.
// Start positions free of crossings therefore give end positions free of
// crossings between cloths, always. Body pairs never stop cloth (cloth
// stopped in front of a moving limb would be swept through and torn):
// where they still fail after the rounds (the body pinches the cloth
// between two of its parts, or sweeps into cloth stopped by the fail-safe)
// the body yields and the pairs are counted. In the body's pinch zones
// (geometry/pinch.h, the zones the measures report crossings in; SweptBody::
// pinch) body pairs are not corrected at all: there two parts of the body
// press the cloth between them, and pushing it out of one pushes it into
// the other and drags or tears it.
//
// All corrections are returned as pushes (the solver adds no velocity for
// them); vertices put back are flagged (the solver stops them).
#pragma once

#include <cstdint>
#include <vector>

#include "box_tree.h"
#include "ccd.h"
#include "contact_candidates.h"
#include "layers/sim/cloth.h"

namespace layers::sim::detail {

constexpr int kZoneRounds = 8;  // rounds of impact zones before the fail-safe

struct CollisionPassStats {
  long pairs = 0;     // colliding pairs found in the first round
  long rounds = 0;    // rounds of corrections run
  long zoned = 0;     // cloth vertices moved rigidly with an impact zone (counted per zone round)
  long reverted = 0;  // cloth vertices put back at their start
  long yielded = 0;   // body pairs the body swept through cloth it could not move
};

// The body as the pass sees it in one substep (null/empty: no body).
struct SweptBody {
  const Vec3s* start = nullptr;  // pose at the start of the substep
  const Vec3s* end = nullptr;    // pose at its end
  const std::vector<std::array<int, 3>>* faces = nullptr;
  const geometry::Edges* edges = nullptr;
  // The whole frame's sweep (the body moves linearly across it) and a
  // number naming that sweep (-1: none): candidate pairs with the body are
  // made once per sweep.
  const Vec3s* frame_start = nullptr;
  const Vec3s* frame_end = nullptr;
  long frame = -1;
  // Per body vertex: in a pinch zone during this frame (null: none), where
  // the body yields to cloth.
  const std::vector<std::uint8_t>* pinch = nullptr;
};

class CollisionPass {
 public:
  // Room each cloth vertex gets in the pass's own candidate list (m).
  static constexpr double kDefaultMargin = 0.002;
  CollisionPass() = default;
  CollisionPass(const CollisionPass&) = delete;  // points into itself
  CollisionPass& operator=(const CollisionPass&) = delete;
  // The layout and candidate list to use, shared with the solver's other
  // contacts (null: the pass's own). The pass sets the list's gap.
  void share(ContactLayout* layout, ContactCandidates* candidates) {
    layout_ = layout != nullptr ? layout : &own_layout_;
    candidates_ = candidates != nullptr ? candidates : &own_candidates_;
  }
  // `states` are the cloths' states (x_start and x; x is corrected in
  // place), in the order of `cloths`. Corrections are added to
  // pushes[cloth]; reverted[cloth][v] tells whether vertex v is put back.
  // With `moved`, the same substep again after a later edit that moved
  // only the flagged vertices (the body as in the last run): only pairs
  // with a moved feature are tested again.
  CollisionPassStats run(const std::vector<Cloth>& cloths, const std::vector<Cloth::State*>& states,
                         const SweptBody& body, double gap, int rounds, std::vector<Vec3s>& pushes,
                         std::vector<std::vector<std::uint8_t>>& reverted,
                         const std::vector<std::vector<std::uint8_t>>* moved = nullptr);

  // One pair whose features came within the gap: its four global vertices
  // (vertex then triangle, or edge then edge) and the CCD stop time.
  struct Hit {
    std::array<int, 4> v;
    bool edge_edge = false;
    double toi = 0;
  };

 private:
  CollisionPassStats resume(const std::vector<Cloth>& cloths, const std::vector<Cloth::State*>& states, double gap,
                            int rounds, std::vector<Vec3s>& pushes, std::vector<std::vector<std::uint8_t>>& reverted,
                            const std::vector<std::vector<std::uint8_t>>& moved);
  // Rounds of corrections, the fail-safe, and the positions written back.
  CollisionPassStats resolve(const std::vector<Cloth::State*>& states, double gap, int rounds,
                             std::vector<Vec3s>& pushes, std::vector<std::vector<std::uint8_t>>& reverted);
  // All pairs (incremental false), or only those with a feature that has a
  // vertex moved since the last detection, plus the last hits with none.
  void detect(double gap, std::vector<Hit>& hits, bool incremental);
  // Pushes the pair apart; false when no vertex of it can move. A body
  // pair with a body vertex in a pinch zone is left alone (the body yields).
  bool correct(const Hit& hit, double gap);
  // Moves each impact zone (the cloth vertices with parent >= 0, grouped by
  // find()) rigidly: its centre of mass as the zone's mean motion, its
  // spin from the zone's angular momentum about the start centre. A zone
  // with a pinned or put-back vertex is left as it is.
  template <class Find>
  void move_zones(std::vector<int>& parent, Find&& find, CollisionPassStats& stats);
  bool test(const std::array<int, 4>& v, bool edge_edge, double gap, std::vector<Hit>& hits) const;
  // A body pair whose cloth feature starts the substep on the body's
  // inside: crossed already, which
  // continuous detection cannot undo; left to the proximity passes.
  bool starts_inside(const std::array<int, 4>& v, bool edge_edge) const;
  bool touched(const int* v, int n) const {
    for (int k = 0; k < n; ++k)
      if (dirty_[v[k]]) return true;
    return false;
  }

  // Everything indexed globally (ContactLayout): cloth vertices first
  // (cloth by cloth), then the body's.
  ContactLayout own_layout_;
  ContactCandidates own_candidates_;
  ContactLayout* layout_ = &own_layout_;
  ContactCandidates* candidates_ = &own_candidates_;
  ContactCandidates::BodySweep sweep_;  // this run's body over its frame

  Vec3s x0_, x1_;                 // start and end of every global vertex
  std::vector<double> inv_mass_;  // 0 for the body and pinned vertices
  std::vector<std::uint8_t> back_;
  std::vector<std::uint8_t> dirty_;  // moved since the last detection
  std::vector<Hit> hits_;            // the pairs of the last detection
  Vec3s body_normals_;               // the body's vertex normals at the start of the substep (area-weighted)
  std::vector<Box> vertex_boxes_, edge_boxes_, face_boxes_;  // the features' swept boxes, grown by half the gap
  std::vector<std::uint8_t> edge_moved_, face_moved_;        // this detection's features with a moved vertex
  SweptBody body_;                                           // this run's body
};

}  // namespace layers::sim::detail
