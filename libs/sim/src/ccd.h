// ccd.h (internal) -- the narrow phase of continuous collision detection:
// does a vertex-triangle or edge-edge pair, each of its four points moving
// on a straight line from its position at the start of a substep to its
// position now, come closer than a minimum separation at some time of the
// substep?
//
// The test follows additive CCD (Li, Kaufman and Jiang, "Codimensional
// Incremental Potential Contact", 2021): the common motion of the four
// points is removed, a bound l on how fast their distance can shrink is
// taken from the remaining displacements, and time advances by
// (1 - s) x (d - xi) / l (s = 0.1), a step that cannot pass a contact,
// until the distance d is within s x xi of xi (a hit, at that time) or
// time runs past the end (no hit). It is conservative: a pair that comes
// within xi is always reported; a pair reported may stay up to 1.1 xi
// apart. Pairs that already start closer than xi are tested against half
// their starting distance; a pair that starts touching (distance 0) and
// moves is a hit at time 0.
#pragma once

#include <array>

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

// Closest points: on triangle (a, b, c) to p, as barycentric weights; and
// between segments p0-p1 and q0-q1, as parameters along each (0 = the
// first end). Both return the squared distance.
double point_triangle_distance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                std::array<double, 3>* bary = nullptr);
double segment_segment_distance2(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, double* s = nullptr,
                                 double* t = nullptr);

// Points 0..3 at the start of the substep (`x0`) and their displacements
// (`dx`): for a vertex-triangle pair the vertex then the triangle's
// corners; for an edge-edge pair one edge's ends then the other's.
struct Sweep {
  std::array<Vec3, 4> x0, dx;
  bool edge_edge = false;
};

// Distance between the pair's features at time t in [0, 1].
double sweep_distance(const Sweep& sweep, double t);

// True when the pair comes within `xi` during [0, 1]; `toi` is then a time
// at which it is still apart (the first time additive CCD stopped).
bool sweep_hits(const Sweep& sweep, double xi, double& toi);

}  // namespace layers::sim::detail
