// garment_section.cpp -- convex hulls, dilation, radial curves of hulls,
// horizontal sections of the envelope and polyline resampling.
#include "layers/garment/garment_section.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "layers/core/error.h"

namespace layers::garment {
namespace {

constexpr double kPi = 3.14159265358979323846;

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

// Distance from c along unit d to where the ray leaves the convex polygon
// (the farthest crossing); 0 when it does not cross.
double ray_exit(const std::vector<Vec2>& hull, const Vec2& c, const Vec2& d) {
  double best = 0;
  const int n = static_cast<int>(hull.size());
  for (int i = 0; i < n; ++i) {
    const Vec2& a = hull[i];
    const Vec2 e = hull[(i + 1) % n] - a;
    const double den = d.x() * e.y() - d.y() * e.x();
    if (std::abs(den) < 1e-15) continue;
    const Vec2 w = a - c;
    const double t = (w.x() * e.y() - w.y() * e.x()) / den;
    const double s = (w.x() * d.y() - w.y() * d.x()) / den;
    if (s >= -1e-9 && s <= 1 + 1e-9) best = std::max(best, t);
  }
  return best;
}

}  // namespace

std::vector<Vec2> convex_hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(),
            [](const Vec2& a, const Vec2& b) { return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y()); });
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
    while (k >= t && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  h.resize(k - 1);
  return h;
}

std::vector<Vec2> dilate(const std::vector<Vec2>& hull, double d) {
  const int n = static_cast<int>(hull.size());
  if (d <= 0 || n == 0) return hull;
  constexpr int kDirections = 24;
  auto angle_of = [](const Vec2& v) {
    const double a = std::atan2(v.y(), v.x());
    return a < 0 ? a + 2 * kPi : a;
  };
  if (n < 3) {  // a point or a segment: the disk around its hull
    std::vector<Vec2> pts;
    for (const Vec2& q : hull)
      for (int k = 0; k < kDirections; ++k)
        pts.push_back(q + d * Vec2(std::cos(2 * kPi * k / kDirections), std::sin(2 * kPi * k / kDirections)));
    return convex_hull(std::move(pts));
  }
  // Minkowski sum with a disk: each vertex of the counter-clockwise hull
  // contributes the arc between the outward normals of its two edges.
  std::vector<Vec2> out;
  out.reserve(n + kDirections + n);
  for (int i = 0; i < n; ++i) {
    const Vec2& v = hull[i];
    const Vec2 in = v - hull[(i + n - 1) % n], next = hull[(i + 1) % n] - v;
    const Vec2 n_in = Vec2(in.y(), -in.x()).normalized(), n_out = Vec2(next.y(), -next.x()).normalized();
    const double a0 = angle_of(n_in);
    double a1 = angle_of(n_out);
    if (a1 < a0) a1 += 2 * kPi;
    out.push_back(v + d * n_in);
    for (int k = static_cast<int>(std::floor(a0 / (2 * kPi) * kDirections)) + 1; 2 * kPi * k / kDirections < a1; ++k) {
      const double a = 2 * kPi * k / kDirections;
      out.push_back(v + d * Vec2(std::cos(a), std::sin(a)));
    }
    out.push_back(v + d * n_out);
  }
  return out;
}

double Radial::radius(double angle) const {
  const int n = static_cast<int>(r.size());
  if (closed) {
    double t = std::fmod(angle, 2 * kPi);
    if (t < 0) t += 2 * kPi;
    const double f = t / (2 * kPi) * n;
    const int i = static_cast<int>(f) % n;
    const double w = f - std::floor(f);
    return (1 - w) * r[i] + w * r[(i + 1) % n];
  }
  const double f = std::clamp((angle - start) / span, 0.0, 1.0) * (n - 1);
  const int i = std::min(static_cast<int>(f), n - 2);
  const double w = f - i;
  return (1 - w) * r[i] + w * r[i + 1];
}

Vec2 Radial::point(double angle) const { return centre + radius(angle) * Vec2(std::cos(angle), std::sin(angle)); }

std::vector<Vec2> Radial::arc(double a0, double a1) const {
  const double step = (closed ? 2 * kPi : span) / std::max<std::size_t>(r.size(), 2) / 2;
  const int n = std::max(2, static_cast<int>(std::ceil(std::abs(a1 - a0) / step)));
  std::vector<Vec2> out;
  out.reserve(n + 1);
  for (int k = 0; k <= n; ++k) out.push_back(point(a0 + (a1 - a0) * k / n));
  return out;
}

Radial radial_of(const std::vector<Vec2>& hull, const Vec2& centre, bool closed, double start, double span, int samples,
                 int smooth) {
  Radial out;
  out.centre = centre;
  out.closed = closed;
  out.start = closed ? 0.0 : start;
  out.span = closed ? 2 * kPi : span;
  const int n = samples;
  std::vector<double> raw(n);
  for (int k = 0; k < n; ++k) {
    const double a = closed ? 2 * kPi * k / n : start + span * k / (n - 1);
    raw[k] = ray_exit(hull, centre, Vec2(std::cos(a), std::sin(a)));
  }
  out.r = raw;
  for (int k = 0; k < n; ++k) {
    double sum = 0;
    int count = 0;
    for (int d = -smooth; d <= smooth; ++d) {
      int i = k + d;
      if (closed)
        i = (i + n) % n;
      else if (i < 0 || i >= n)
        continue;
      sum += raw[i];
      ++count;
    }
    // Smoothing may only move the curve outwards (it must keep enclosing).
    out.r[k] = std::max(raw[k], sum / count);
  }
  return out;
}

Radial horizontal_section(const Envelope& env, double y, const SectionSpec& spec) {
  std::vector<Vec2> pts;
  const double top = y + spec.slab + (spec.hang > 0 ? spec.hang_reach : 0.0);
  std::vector<std::pair<Vec2, double>> above;  // (x, z), height above the slab
  for (int i : env.slab(1, y - spec.slab, top, spec.parts)) {
    const body::Vec3& p = env.point(i);
    if (spec.side > 0 && p.x() < 0) continue;
    if (p.y() <= y + spec.slab)
      pts.emplace_back(p.x(), p.z());
    else
      above.emplace_back(Vec2(p.x(), p.z()), p.y() - y - spec.slab);
  }
  if (pts.size() < 3) throw Error("garment section: no body points near height " + std::to_string(y));
  if (!above.empty()) {
    Vec2 lo = pts[0], hi = pts[0];
    for (const Vec2& q : pts) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const Vec2 mid = 0.5 * (lo + hi);
    for (const auto& [q, dy] : above) {
      const double r = (q - mid).norm(), in = spec.hang * dy;
      if (r > in) pts.push_back(mid + (q - mid) * ((r - in) / r));
    }
  }
  const std::vector<Vec2> hull = dilate(convex_hull(std::move(pts)), spec.ease);
  Vec2 lo = hull[0], hi = hull[0];
  for (const Vec2& q : hull) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  Vec2 centre = 0.5 * (lo + hi);
  if (spec.centre_on_midline) centre.x() = 0.0;
  return radial_of(hull, centre, true, 0.0, 0.0, 180, 2);
}

double length(const std::vector<body::Vec3>& line) {
  double s = 0;
  for (std::size_t i = 1; i < line.size(); ++i) s += (line[i] - line[i - 1]).norm();
  return s;
}

double length(const std::vector<Vec2>& line) {
  double s = 0;
  for (std::size_t i = 1; i < line.size(); ++i) s += (line[i] - line[i - 1]).norm();
  return s;
}

std::vector<body::Vec3> resample(const std::vector<body::Vec3>& line, int n) {
  std::vector<double> fractions(n + 1);
  for (int i = 0; i <= n; ++i) fractions[i] = static_cast<double>(i) / n;
  return resample_at(line, fractions);
}

std::vector<body::Vec3> resample_at(const std::vector<body::Vec3>& line, const std::vector<double>& fractions) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  std::vector<body::Vec3> out;
  out.reserve(fractions.size());
  for (double fraction : fractions) {
    const double t = s.back() * std::clamp(fraction, 0.0, 1.0);
    const std::size_t k = std::min<std::size_t>(
        std::max<std::size_t>(1, static_cast<std::size_t>(std::lower_bound(s.begin(), s.end(), t) - s.begin())),
        s.size() - 1);
    const double len = s[k] - s[k - 1];
    const double f = len > 0 ? std::clamp((t - s[k - 1]) / len, 0.0, 1.0) : 0.0;
    out.push_back(line[k - 1] + f * (line[k] - line[k - 1]));
  }
  if (!fractions.empty() && fractions.front() <= 0) out.front() = line.front();
  if (!fractions.empty() && fractions.back() >= 1) out.back() = line.back();
  return out;
}

std::vector<body::Vec3> at_height(const std::vector<Vec2>& xz, double y) {
  std::vector<body::Vec3> out;
  out.reserve(xz.size());
  for (const Vec2& q : xz) out.emplace_back(q.x(), y, q.y());
  return out;
}

std::vector<body::Vec3> at_abscissa(const std::vector<Vec2>& zy, double x) {
  std::vector<body::Vec3> out;
  out.reserve(zy.size());
  for (const Vec2& q : zy) out.emplace_back(x, q.y(), q.x());
  return out;
}

double smooth01(double t) {
  t = std::clamp(t, 0.0, 1.0);
  return t * t * (3 - 2 * t);
}

}  // namespace layers::garment
