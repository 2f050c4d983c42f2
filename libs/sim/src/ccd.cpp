// Narrow phase of continuous collision detection (see ccd.h): closest
// points of a vertex and a triangle and of two segments (Voronoi-region
// case analysis, as in Ericson's "Real-Time Collision Detection"), and the
// additive CCD loop over them.
#include "ccd.h"

#include <algorithm>
#include <cmath>

namespace layers::sim::detail {

namespace {

// Steps of additive CCD before the pair is reported as a hit anyway (at
// the time reached): pairs that creep towards each other for this long are
// resolved by the caller, which is the safe side.
constexpr int kMaxSteps = 500;
// Each step advances (1 - kShrink) of the time the gap could last; a hit
// is a distance within kShrink x sep of sep.
constexpr double kShrink = 0.1;

double clamp01(double v) { return v < 0 ? 0 : (v > 1 ? 1 : v); }

}  // namespace

double point_triangle_distance2(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c,
                                std::array<double, 3>* bary) {
  const Vec3 ab = b - a, ac = c - a, ap = p - a;
  std::array<double, 3> w{1, 0, 0};
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) {
    w = {1, 0, 0};
  } else {
    const Vec3 bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    const Vec3 cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    const double vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) {
      w = {0, 1, 0};
    } else if (d6 >= 0 && d5 <= d6) {
      w = {0, 0, 1};
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      const double v = d1 / (d1 - d3);
      w = {1 - v, v, 0};
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      const double v = d2 / (d2 - d6);
      w = {1 - v, 0, v};
    } else if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
      const double v = (d4 - d3) / ((d4 - d3) + (d5 - d6));
      w = {0, 1 - v, v};
    } else {
      const double denom = va + vb + vc;
      if (!(std::abs(denom) > 0)) {
        // Degenerate triangle: the nearest of its three edges.
        double s = 0;
        double best = segment_segment_distance2(p, p, a, b, nullptr, &s);
        w = {1 - s, s, 0};
        double d = segment_segment_distance2(p, p, a, c, nullptr, &s);
        if (d < best) best = d, w = {1 - s, 0, s};
        d = segment_segment_distance2(p, p, b, c, nullptr, &s);
        if (d < best) best = d, w = {0, 1 - s, s};
      } else {
        const double v = vb / denom, u = vc / denom;
        w = {1 - v - u, v, u};
      }
    }
  }
  if (bary) *bary = w;
  return (p - (w[0] * a + w[1] * b + w[2] * c)).squaredNorm();
}

double segment_segment_distance2(const Vec3& p0, const Vec3& p1, const Vec3& q0, const Vec3& q1, double* s_out,
                                 double* t_out) {
  const Vec3 d1 = p1 - p0, d2 = q1 - q0, r = p0 - q0;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0, t = 0;
  if (a <= 0 && e <= 0) {
    s = t = 0;
  } else if (a <= 0) {
    s = 0;
    t = clamp01(f / e);
  } else {
    const double c = d1.dot(r);
    if (e <= 0) {
      t = 0;
      s = clamp01(-c / a);
    } else {
      const double b = d1.dot(d2);
      const double denom = a * e - b * b;
      s = denom > 0 ? clamp01((b * f - c * e) / denom) : 0.0;
      t = (b * s + f) / e;
      if (t < 0) {
        t = 0;
        s = clamp01(-c / a);
      } else if (t > 1) {
        t = 1;
        s = clamp01((b - c) / a);
      }
    }
  }
  if (s_out) *s_out = s;
  if (t_out) *t_out = t;
  return (p0 + s * d1 - (q0 + t * d2)).squaredNorm();
}

namespace {

double distance_of(const std::array<Vec3, 4>& x, bool edge_edge) {
  return std::sqrt(edge_edge ? segment_segment_distance2(x[0], x[1], x[2], x[3])
                             : point_triangle_distance2(x[0], x[1], x[2], x[3]));
}

}  // namespace

double sweep_distance(const Sweep& sweep, double t) {
  std::array<Vec3, 4> x;
  for (int k = 0; k < 4; ++k) x[k] = sweep.x0[k] + t * sweep.dx[k];
  return distance_of(x, sweep.edge_edge);
}

bool sweep_hits(const Sweep& sweep, double xi, double& toi) {
  toi = 0;
  // Positions relative to point 0's start (fewer cancellations), motions
  // relative to the mean motion (a shared translation cannot close a gap).
  std::array<Vec3, 4> x, dx;
  Vec3 mean = Vec3::Zero();
  for (int k = 0; k < 4; ++k) mean += sweep.dx[k];
  mean /= 4;
  for (int k = 0; k < 4; ++k) {
    x[k] = sweep.x0[k] - sweep.x0[0];
    dx[k] = sweep.dx[k] - mean;
  }
  double bound;
  if (sweep.edge_edge) {
    bound = std::max(dx[0].norm(), dx[1].norm()) + std::max(dx[2].norm(), dx[3].norm());
  } else {
    bound = dx[0].norm() + std::max({dx[1].norm(), dx[2].norm(), dx[3].norm()});
  }
  if (!(bound > 0)) return false;  // rigidly moving together: the distance cannot change
  if (!std::isfinite(bound)) return true;
  // A cheap lower bound of the starting distance first (bounding spheres
  // of the two features): most candidates of the broad phase end here.
  Vec3 ca, cb;
  double ra = 0, rb = 0;
  if (sweep.edge_edge) {
    ca = 0.5 * (x[0] + x[1]);
    cb = 0.5 * (x[2] + x[3]);
    ra = 0.5 * (x[1] - x[0]).norm();
    rb = 0.5 * (x[3] - x[2]).norm();
  } else {
    ca = x[0];
    cb = (x[1] + x[2] + x[3]) / 3;
    rb = std::sqrt(std::max({(x[1] - cb).squaredNorm(), (x[2] - cb).squaredNorm(), (x[3] - cb).squaredNorm()}));
  }
  if ((ca - cb).norm() - ra - rb - bound > xi) return false;
  double d = distance_of(x, sweep.edge_edge);
  if (!(d > 0)) return true;  // touching at the start and moving
  const double sep = std::min(xi, 0.5 * d);
  const double tolerance = kShrink * sep;
  const std::array<Vec3, 4> start = x;
  double t = 0;
  for (int step = 0; step < kMaxSteps; ++step) {
    // No contact can happen within this step: the distance shrinks by at
    // most bound x step = (1 - s)(d - sep), leaving at least s(d - sep).
    t += (1 - kShrink) * (d - sep) / bound;
    if (t > 1) return false;
    for (int k = 0; k < 4; ++k) x[k] = start[k] + t * dx[k];
    d = distance_of(x, sweep.edge_edge);
    if (d - sep < tolerance) {
      toi = t;
      return true;
    }
  }
  toi = t;
  return true;
}

}  // namespace layers::sim::detail
