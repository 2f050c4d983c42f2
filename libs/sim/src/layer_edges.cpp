// Edge-edge proximity between an inner and an outer garment (see
// cloth_contact.h, EdgeContact).
#include <algorithm>
#include <cmath>

#include "cloth_contact.h"

namespace layers::sim::detail {

namespace {

// Closest points p0 + s (p1 - p0) and q0 + t (q1 - q0) of two segments
// (s, t in [0, 1]).
void closest_on_segments(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, double& s, double& t) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  const double c = d1.dot(r), b = d1.dot(d2);
  const double denom = a * e - b * b;
  // Parallel (or degenerate) segments: any s works; start from 0.
  s = (denom > 1e-18 * a * e && a > 0) ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
  t = e > 0 ? (b * s + f) / e : 0.0;
  if (t < 0) {
    t = 0;
    s = a > 0 ? std::clamp(-c / a, 0.0, 1.0) : 0.0;
  } else if (t > 1) {
    t = 1;
    s = a > 0 ? std::clamp((b - c) / a, 0.0, 1.0) : 0.0;
  }
}

}  // namespace

void EdgeContact::collide(const Cloth& inner, Cloth::State& in, const std::vector<double>& w_in, const Cloth& outer,
                          Cloth::State& out, double thickness, Vec3s& inner_push, Vec3s& outer_push) {
  const geometry::Edges& ei = inner.edges();
  const geometry::Edges& eo = outer.edges();
  if (ei.rows() == 0 || eo.rows() == 0) return;
  // Broad phase: each inner edge's box (grown by the thickness) is filed
  // under every grid cell it overlaps; an outer edge meets the inner edges
  // filed under the cells of its own box (each once: `seen_`).
  const double cell = std::max(0.5 * inner.topology().max_edge_length, 1e-6);
  cells_.build(ei, in.x, thickness, cell);
  seen_.assign(static_cast<std::size_t>(ei.rows()), -1);
  const std::vector<double>& w_out = out.inv_mass;
  for (Eigen::Index k = 0; k < eo.rows(); ++k) {
    const int a = eo(k, 0), b = eo(k, 1);
    const Vec3 lo = out.x[a].cwiseMin(out.x[b]), hi = out.x[a].cwiseMax(out.x[b]);
    cells_.visit(lo, hi, [&](int e) {
      if (seen_[e] == k) return;
      seen_[e] = static_cast<int>(k);
      const int c = ei(e, 0), d = ei(e, 1);
      // Boxes (the inner one grown by the thickness) must overlap.
      const Vec3 ilo = in.x[c].cwiseMin(in.x[d]).array() - thickness;
      const Vec3 ihi = in.x[c].cwiseMax(in.x[d]).array() + thickness;
      if ((lo.array() > ihi.array()).any() || (hi.array() < ilo.array()).any()) return;
      double s, t;
      closest_on_segments(out.x[a], out.x[b], in.x[c], in.x[d], s, t);
      const Vec3 p = out.x[a] + s * (out.x[b] - out.x[a]), q = in.x[c] + t * (in.x[d] - in.x[c]);
      const Vec3 delta = p - q;
      if (delta.squaredNorm() >= thickness * thickness) return;
      // Which side the outer edge was on at the start of the substep, at
      // the same pair of points: it must stay there.
      const Vec3 p0 = out.x_start[a] + s * (out.x_start[b] - out.x_start[a]);
      const Vec3 q0 = in.x_start[c] + t * (in.x_start[d] - in.x_start[c]);
      Vec3 n = p0 - q0;
      double len = n.norm();
      if (!(len > 1e-9)) {
        n = delta;
        len = n.norm();
        if (!(len > 1e-9)) return;
      }
      n /= len;
      const double depth = thickness - delta.dot(n);
      if (depth <= 0) return;
      const double weight =
          w_out[a] * (1 - s) * (1 - s) + w_out[b] * s * s + w_in[c] * (1 - t) * (1 - t) + w_in[d] * t * t;
      if (!(weight > 0)) return;
      const double lambda = depth / weight;
      const auto move = [&](Vec3s& x, Vec3s& push, int v, double amount) {
        x[v] += amount * n;
        push[v] += amount * n;
      };
      move(out.x, outer_push, a, w_out[a] * (1 - s) * lambda);
      move(out.x, outer_push, b, w_out[b] * s * lambda);
      move(in.x, inner_push, c, -w_in[c] * (1 - t) * lambda);
      move(in.x, inner_push, d, -w_in[d] * t * lambda);
    });
  }
}

void EdgeContact::Cells::build(const geometry::Edges& edges, const Vec3s& x, double grow, double cell) {
  inv_cell = 1.0 / cell;
  std::size_t slots = 1;
  while (slots < 2 * static_cast<std::size_t>(edges.rows())) slots <<= 1;
  mask = slots - 1;
  start.assign(slots + 1, 0);
  const auto each_cell = [&](Eigen::Index e, auto&& f) {
    const Vec3& u = x[edges(e, 0)];
    const Vec3& v = x[edges(e, 1)];
    if (!u.allFinite() || !v.allFinite()) return;
    const Vec3 lo = u.cwiseMin(v).array() - grow, hi = u.cwiseMax(v).array() + grow;
    for_cells(lo, hi, f);
  };
  for (Eigen::Index e = 0; e < edges.rows(); ++e) each_cell(e, [&](std::uint32_t s) { ++start[s + 1]; });
  for (std::size_t s = 0; s < slots; ++s) start[s + 1] += start[s];
  entries.resize(static_cast<std::size_t>(start[slots]));
  fill = start;
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    each_cell(e, [&](std::uint32_t s) { entries[fill[s]++] = static_cast<int>(e); });
}

}  // namespace layers::sim::detail
