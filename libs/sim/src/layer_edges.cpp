// Edge-edge proximity between an inner surface (a garment or the body) and
// an outer garment (see cloth_contact.h, EdgeContact).
#include <algorithm>
#include <cmath>

#include "ccd.h"
#include "cloth_contact.h"

namespace layers::sim::detail {

double EdgeContact::collide(const Side& inner, const Side& outer, double thickness,
                            const std::vector<std::array<int, 2>>& pairs) {
  const geometry::Edges& ei = *inner.edges;
  const geometry::Edges& eo = *outer.edges;
  if (ei.rows() == 0 || eo.rows() == 0 || outer.x == nullptr) return 0.0;
  Vec3s& xo = *outer.x;
  const Vec3s& xi = inner.now();
  const Vec3s &so = *outer.start, &si = *inner.start;
  const std::vector<double>& w_out = *outer.inv_mass;
  const bool inner_moves = inner.x != nullptr;
  const auto w_in = [&](int v) { return inner_moves ? (*inner.inv_mass)[v] : 0.0; };
  double largest = 0;
  for (const auto& [k, e] : pairs) {
    const int a = eo(k, 0), b = eo(k, 1);
    const Vec3 lo = xo[a].cwiseMin(xo[b]), hi = xo[a].cwiseMax(xo[b]);
    const int c = ei(e, 0), d = ei(e, 1);
    // Boxes (the inner one grown by the thickness) must overlap.
    const Vec3 ilo = xi[c].cwiseMin(xi[d]).array() - thickness;
    const Vec3 ihi = xi[c].cwiseMax(xi[d]).array() + thickness;
    if ((lo.array() > ihi.array()).any() || (hi.array() < ilo.array()).any()) continue;
    // Bounding spheres: edges whose spheres stand farther apart than the
    // thickness (with room for rounding) cannot come within it.
    const double apart =
        (0.5 * (xo[a] + xo[b] - xi[c] - xi[d])).norm() - 0.5 * (xo[b] - xo[a]).norm() - 0.5 * (xi[d] - xi[c]).norm();
    if (apart > thickness * (1 + 1e-9) + 1e-12) continue;
    double s, t;
    segment_segment_distance2(xo[a], xo[b], xi[c], xi[d], &s, &t);
    const Vec3 p = xo[a] + s * (xo[b] - xo[a]), q = xi[c] + t * (xi[d] - xi[c]);
    const Vec3 delta = p - q;
    if (delta.squaredNorm() >= thickness * thickness) continue;
    // Which side the outer edge was on at the start of the substep, at
    // the same pair of points: it must stay there.
    const Vec3 p0 = so[a] + s * (so[b] - so[a]);
    const Vec3 q0 = si[c] + t * (si[d] - si[c]);
    Vec3 n = p0 - q0;
    double len = n.norm();
    if (!(len > 1e-9)) {
      n = delta;
      len = n.norm();
    }
    if (inner.outward != nullptr) {
      // An edge already on the inner surface's inside goes out.
      const Vec3& out = (*inner.outward)[e];
      if (out.squaredNorm() > 0 && (!(len > 1e-9) || n.dot(out) < 0)) {
        n = out;
        len = 1;
      }
    }
    if (!(len > 1e-9)) continue;
    n /= len;
    const double depth = thickness - delta.dot(n);
    if (depth <= 0) continue;
    const double weight =
        w_out[a] * (1 - s) * (1 - s) + w_out[b] * s * s + w_in(c) * (1 - t) * (1 - t) + w_in(d) * t * t;
    if (!(weight > 0)) continue;
    const double lambda = depth / weight;
    const auto move = [&](Vec3s& x, Vec3s* push, int v, double amount) {
      x[v] += amount * n;
      if (push != nullptr) (*push)[v] += amount * n;
    };
    move(xo, outer.push, a, w_out[a] * (1 - s) * lambda);
    move(xo, outer.push, b, w_out[b] * s * lambda);
    largest = std::max(largest, std::max(w_out[a] * (1 - s), w_out[b] * s) * lambda);
    if (inner_moves) {
      move(*inner.x, inner.push, c, -w_in(c) * (1 - t) * lambda);
      move(*inner.x, inner.push, d, -w_in(d) * t * lambda);
    }
  }
  return largest;
}

}  // namespace layers::sim::detail
