// layers/body/skin_untangle.h -- pushing a posed skin out of itself where
// it passes through itself.
//
// Linear blend skinning folds the skin into itself where a joint bends:
// the groin and the buttocks when the hip flexes, the armpits, the elbow
// and knee pits, thighs pressed together. A garment laid over such a fold
// has to cross one of its sheets (docs/sim.md, "body-self"). Each round,
// SkinUntangler finds the pairs of skin faces that cross (exactly,
// geometry::visit_crossings; pairs sharing a vertex skipped), pushes every
// vertex of either face that lies behind the other face's plane out along
// that face's normal (half the depth plus half a margin: each sheet takes
// half of the way), then takes a few Taubin lambda/mu smoothing steps over
// the pushed vertices and their neighbours so that no spike is left. It
// stops after `passes` rounds, when nothing crosses or after three rounds
// without progress, and keeps the round
// with the fewest crossings (a push can make new ones). Hands, feet and
// the head (vertices carried mostly by a hand, finger, thumb, foot, toe or
// head bone) never move and their faces are left out of the count: they
// carry no garment, and fingers and toes touch by design. Frames are
// untangled one by one (no temporal coupling).
#pragma once

#include <vector>

#include "layers/body/body_model.h"
#include "layers/geometry/mesh.h"
#include "layers/geometry/topology.h"

namespace layers::body {

struct SkinUntangleOptions {
  int passes = 0;          // rounds of detect, push and smooth per frame; 0 = off
  double margin = 0.0005;  // m past the other sheet that a pushed vertex goes
  int steps = 3;           // lambda/mu step pairs per round
  double lambda = 0.5;     // Taubin's shrinking step ...
  double mu = -0.53;       // ... and the inflating one that follows it
};

// Faces count when they and the face they cross are off the hands, feet
// and head.
struct SkinUntangleResult {
  int crossing_before = 0;  // skin faces passing through another skin face, before
  int crossing_after = 0;   // and after (the best round's)
  int moved = 0;            // vertices smoothed at least once
};

// Keeps its own copy of what it needs of `body` (faces, adjacency, which
// vertices may move).
class SkinUntangler {
 public:
  explicit SkinUntangler(const Body& body);
  // Smooths `vertices` (the body's skin, posed) in place.
  SkinUntangleResult apply(geometry::Points& vertices, const SkinUntangleOptions& options) const;
  // Whether vertex v may move (not on a hand or a foot).
  bool movable(int v) const { return movable_[v] != 0; }
  // Skin faces off the hands, feet and head that pass through another such
  // face (what the result counts).
  int crossing_faces(const geometry::Points& vertices) const;

 private:
  geometry::Faces faces_;
  geometry::Adjacency adjacency_;
  std::vector<char> movable_, movable_face_;  // per vertex, per face (all three vertices movable)
};

}  // namespace layers::body
