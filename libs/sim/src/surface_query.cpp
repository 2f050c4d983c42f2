// Point-triangle closest points and the one-ring surface query (see
// surface_query.h).
#include "surface_query.h"

#include <cmath>
#include <limits>

namespace layers::sim::detail {

TrianglePoint closest_on_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c) {
  // Voronoi regions of the triangle, tested vertex by vertex, then edges.
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return {a, {1, 0, 0}, TrianglePoint::Vertex0};
  const Vec3 bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return {b, {0, 1, 0}, TrianglePoint::Vertex1};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double t = d1 / (d1 - d3);
    return {a + t * ab, {1 - t, t, 0}, TrianglePoint::Edge0};
  }
  const Vec3 cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return {c, {0, 0, 1}, TrianglePoint::Vertex2};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double t = d2 / (d2 - d6);
    return {a + t * ac, {1 - t, 0, t}, TrianglePoint::Edge2};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double t = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {b + t * (c - b), {0, 1 - t, t}, TrianglePoint::Edge1};
  }
  const double inv = 1.0 / (va + vb + vc);
  const double v = vb * inv, w = vc * inv;
  return {a + v * ab + w * ac, {1 - v - w, v, w}, TrianglePoint::Face};
}

bool closest_around(const ContactTopology& t, const Vec3s& x, int center, const Vec3& p, SurfaceHit& hit) {
  double best = std::numeric_limits<double>::infinity();
  TrianglePoint best_point{};
  Vec3 best_normal = Vec3::Zero();
  int best_face = -1;
  for (int i = t.face_offsets[center]; i < t.face_offsets[center + 1]; ++i) {
    const int f = t.vertex_faces[i];
    const auto& v = t.faces[f];
    const TrianglePoint q = closest_on_triangle(p, x[v[0]], x[v[1]], x[v[2]]);
    const double d2 = (p - q.point).squaredNorm();
    if (d2 < best) {
      // Degenerate faces are left out; the normal is needed only for a
      // face that would be kept.
      const Vec3 n = (x[v[1]] - x[v[0]]).cross(x[v[2]] - x[v[0]]);
      if (!(n.squaredNorm() > 0)) continue;
      best = d2;
      best_point = q;
      best_normal = n;  // normalised once, for the face kept
      best_face = f;
    }
  }
  if (best_face < 0) return false;
  best_normal /= best_normal.norm();
  hit.face = best_face;
  hit.bary = best_point.bary;
  hit.point = best_point.point;
  const Vec3 d = p - best_point.point;
  const double dist = std::sqrt(best);
  if (best_point.region == TrianglePoint::Face || dist < 1e-12) {
    hit.normal = best_normal;
    hit.offset = d.dot(best_normal);
  } else {
    const double side = d.dot(best_normal) >= 0 ? 1.0 : -1.0;
    hit.normal = (side / dist) * d;
    hit.offset = side * dist;
  }
  const auto& v = t.faces[best_face];
  hit.facing = best_point.region == TrianglePoint::Face || std::abs(d.dot(best_normal)) >= 0.7 * dist;
  switch (best_point.region) {
    case TrianglePoint::Face:
      hit.on_boundary = false;
      break;
    case TrianglePoint::Vertex0:
      hit.on_boundary = t.boundary_vertex[v[0]] != 0;
      break;
    case TrianglePoint::Vertex1:
      hit.on_boundary = t.boundary_vertex[v[1]] != 0;
      break;
    case TrianglePoint::Vertex2:
      hit.on_boundary = t.boundary_vertex[v[2]] != 0;
      break;
    case TrianglePoint::Edge0:
      hit.on_boundary = (t.boundary_edges[best_face] & 1u) != 0;
      break;
    case TrianglePoint::Edge1:
      hit.on_boundary = (t.boundary_edges[best_face] & 2u) != 0;
      break;
    case TrianglePoint::Edge2:
      hit.on_boundary = (t.boundary_edges[best_face] & 4u) != 0;
      break;
  }
  return true;
}

double side_offset(const ContactTopology& t, const Vec3s& x, const SurfaceHit& hit, const Vec3& p) {
  const auto& f = t.faces[hit.face];
  const Vec3 a = x[f[0]], b = x[f[1]], c = x[f[2]];
  const Vec3 n = (b - a).cross(c - a);
  const double len = n.norm();
  if (!(len > 0)) return 0.0;
  const Vec3 q = hit.bary[0] * a + hit.bary[1] * b + hit.bary[2] * c;
  return (p - q).dot(n) / len;
}

}  // namespace layers::sim::detail
