// contact_response.h (internal) -- position-based contact with Coulomb
// friction, shared by every contact kind. A contact moves points along the
// unit normal n by `depth` (the violation, > 0) split by inverse mass, then
// removes the tangential part of the relative displacement over the
// substep: fully when it is within mu * depth (static friction), else by
// mu * depth (kinetic), split the same way.
#pragma once

#include <array>
#include <cmath>

#include "layers/sim/cloth.h"
#include "surface_query.h"

namespace layers::sim::detail {

// The tangential correction for relative displacement `rel` (to be
// subtracted from the relative motion); `slid` tells whether it was limited
// by the cone (kinetic friction).
inline Vec3 friction_correction(const Vec3& rel, const Vec3& n, double depth, double mu, bool* slid = nullptr) {
  const Vec3 tangential = rel - rel.dot(n) * n;
  const double len = tangential.norm();
  const double limit = mu * depth;
  if (slid) *slid = len > limit;
  if (len <= limit) return tangential;
  return tangential * (limit / len);
}

// A vertex against a kinematic surface whose contact point moved by
// `surface_motion` during the substep; returns true if it slid.
inline bool resolve_kinematic(Vec3& x, const Vec3& x_start, const Vec3& n, double depth, const Vec3& surface_motion,
                              double mu) {
  bool slid = false;
  x += depth * n;
  x -= friction_correction((x - x_start) - surface_motion, n, depth, mu, &slid);
  return slid;
}

// A vertex p against the point sum_k b[k] y[k] of a triangle of another
// (or the same) cloth; both sides move, weighted by inverse mass. The
// normal points from the triangle towards where p must go.
struct TriangleRef {
  std::array<int, 3> v;
  std::array<double, 3> b;
};

// The normal pushes are also added to `push_p` and `push_t` (see
// Solver: they move positions without adding velocity).
inline void resolve_two_way(Vec3s& xp, const Vec3s& xp_start, const std::vector<double>& wp, int p, Vec3s& xt,
                            const Vec3s& xt_start, const std::vector<double>& wt, const TriangleRef& tri, const Vec3& n,
                            double depth, double mu, Vec3s& push_p, Vec3s& push_t) {
  double weight = wp[p];
  for (int k = 0; k < 3; ++k) weight += tri.b[k] * tri.b[k] * wt[tri.v[k]];
  if (!(weight > 0)) return;
  const double lambda = depth / weight;
  xp[p] += (wp[p] * lambda) * n;
  push_p[p] += (wp[p] * lambda) * n;
  for (int k = 0; k < 3; ++k) {
    xt[tri.v[k]] -= (wt[tri.v[k]] * tri.b[k] * lambda) * n;
    push_t[tri.v[k]] -= (wt[tri.v[k]] * tri.b[k] * lambda) * n;
  }

  Vec3 rel = xp[p] - xp_start[p];
  for (int k = 0; k < 3; ++k) rel -= tri.b[k] * (xt[tri.v[k]] - xt_start[tri.v[k]]);
  const Vec3 c = friction_correction(rel, n, depth, mu) / weight;
  xp[p] -= wp[p] * c;
  for (int k = 0; k < 3; ++k) xt[tri.v[k]] += (wt[tri.v[k]] * tri.b[k]) * c;
}

// The push of a cloth vertex away from another cloth surface (or its own)
// at `hit`. Where the vertex faces the surface (above or below it, see
// SurfaceHit::facing), it is kept `thickness` on side `side` (+1: the normal
// side, -1: behind). Where it is beside an edge or a corner -- past a hem,
// or beside a fold -- "which side" is not defined, so the edge or corner is
// only kept `thickness` away in any direction. Returns false when nothing needs doing, else sets the
// direction and depth.
inline bool cloth_push(const SurfaceHit& hit, const Vec3& p, double side, double thickness, Vec3& normal,
                       double& depth) {
  if (!hit.facing) {
    const Vec3 d = p - hit.point;
    const double dist = d.norm();
    if (dist >= thickness || !(dist > 1e-9)) return false;
    normal = d / dist;
    depth = thickness - dist;
    return true;
  }
  const double offset = side * hit.offset;
  if (offset >= thickness) return false;
  normal = side * hit.normal;
  depth = thickness - offset;
  return true;
}

}  // namespace layers::sim::detail
