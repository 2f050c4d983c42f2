// surface_query.h (internal) -- the closest point of a triangle mesh to a
// query point, searched among the faces around one vertex (the nearest
// mesh vertex, found through a SpatialHash). Shared by the body, layer and
// self contacts.
#pragma once

#include <array>

#include "layers/sim/cloth.h"
#include "layers/sim/contact_topology.h"

namespace layers::sim::detail {

// Closest point of triangle (a, b, c) to p, with barycentric weights and
// the feature it lies on.
struct TrianglePoint {
  enum Region { Face, Vertex0, Vertex1, Vertex2, Edge0, Edge1, Edge2 };  // edge k: corner k -> k+1
  Vec3 point;
  std::array<double, 3> bary;
  Region region;
};
TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

struct SurfaceHit {
  int face = -1;
  std::array<double, 3> bary{};
  Vec3 point = Vec3::Zero();
  // Unit contact normal on the side the face normal points to: the face
  // normal when the closest point is inside the face, else the direction
  // from the closest point to p, signed to the face's side.
  Vec3 normal = Vec3::Zero();
  double offset = 0;  // (p - point) . normal: signed distance
  // The closest point is inside the face, or p lies mostly along the face
  // normal from it (above or below the surface rather than beside it).
  bool facing = false;
  bool on_boundary = false;  // the closest feature is an open-boundary edge or vertex
};

// Searches the faces around `center` (positions x); false if it has none
// with a non-zero area. Ties keep the first face in topology order.
bool closest_around(const ContactTopology& topology, const Vec3s& x, int center, const Vec3& p, SurfaceHit& hit);

// Signed distance of `p` from the plane of `hit`'s face, all taken at the
// positions `x` (e.g. those at the start of the substep): which side of the
// surface p was on.
double side_offset(const ContactTopology& topology, const Vec3s& x, const SurfaceHit& hit, const Vec3& p);

}  // namespace layers::sim::detail
