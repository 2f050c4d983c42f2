// garment_triangulate.cpp -- constrained Delaunay meshing of a panel
// polygon: ear clipping of the outline, Lawson flips to the constrained
// Delaunay triangulation, incremental insertion of lattice points (walk
// location, split, legalise), then Laplacian smoothing with flips.
#include "layers/garment/garment_triangulate.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>

#include "layers/core/error.h"

namespace layers::garment {
namespace {

double orient(const Vec2& a, const Vec2& b, const Vec2& c) {
  return (b.x() - a.x()) * (c.y() - a.y()) - (b.y() - a.y()) * (c.x() - a.x());
}

// > 0 when d lies inside the circumcircle of the counter-clockwise a, b, c.
double incircle(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d) {
  const double adx = a.x() - d.x(), ady = a.y() - d.y();
  const double bdx = b.x() - d.x(), bdy = b.y() - d.y();
  const double cdx = c.x() - d.x(), cdy = c.y() - d.y();
  const double ad = adx * adx + ady * ady, bd = bdx * bdx + bdy * bdy, cd = cdx * cdx + cdy * cdy;
  return adx * (bdy * cd - bd * cdy) - ady * (bdx * cd - bd * cdx) + ad * (bdx * cdy - bdy * cdx);
}

double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double len2 = ab.squaredNorm();
  const double t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0, 1.0) : 0.0;
  return (p - (a + t * ab)).norm();
}

bool inside_polygon(const Vec2& p, const std::vector<Vec2>& poly) {
  bool in = false;
  for (std::size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const Vec2& a = poly[i];
    const Vec2& b = poly[j];
    if ((a.y() > p.y()) != (b.y() > p.y()) && p.x() < (b.x() - a.x()) * (p.y() - a.y()) / (b.y() - a.y()) + a.x())
      in = !in;
  }
  return in;
}

// A deterministic tiny offset in [-0.5, 0.5) per lattice point, so that no
// four points are exactly cocircular and no point lies exactly on an edge.
double hash_unit(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  x ^= x >> 31;
  return static_cast<double>(x >> 11) * (1.0 / 9007199254740992.0) - 0.5;
}

struct Tri {
  std::array<int, 3> v;  // counter-clockwise
  std::array<int, 3> n;  // n[k]: neighbour across the edge opposite v[k]; -1 on the outline
};

class Triangulation {
 public:
  explicit Triangulation(std::vector<Vec2>& pts) : p_(pts) {}

  void ear_clip(int n);
  void make_delaunay();
  bool insert(int point);
  void smooth(int num_boundary, int rounds, double min_area);
  std::vector<std::array<int, 3>> triangles() const {
    std::vector<std::array<int, 3>> out;
    out.reserve(t_.size());
    for (const Tri& t : t_) out.push_back(t.v);
    return out;
  }

 private:
  int slot_of(int tri, int vertex) const {
    for (int k = 0; k < 3; ++k)
      if (t_[tri].v[k] == vertex) return k;
    return -1;
  }
  // Index k in `tri` of the neighbour pointer that points to `other`.
  int link_of(int tri, int other) const {
    for (int k = 0; k < 3; ++k)
      if (t_[tri].n[k] == other) return k;
    return -1;
  }
  void relink(int tri, int from, int to) {
    if (tri < 0) return;
    const int k = link_of(tri, from);
    if (k >= 0) t_[tri].n[k] = to;
  }
  bool needs_flip(int tri, int k) const;
  void flip(int tri, int k);
  void legalise(int tri, int point);
  int locate(const Vec2& q) const;

  std::vector<Vec2>& p_;
  std::vector<Tri> t_;
  mutable int last_ = 0;
};

void Triangulation::ear_clip(int n) {
  std::vector<int> prev(n), next(n);
  for (int i = 0; i < n; ++i) {
    prev[i] = (i + n - 1) % n;
    next[i] = (i + 1) % n;
  }
  auto is_ear = [&](int i) {
    const Vec2 &a = p_[prev[i]], &b = p_[i], &c = p_[next[i]];
    if (orient(a, b, c) <= 0) return false;
    for (int j = next[next[i]]; j != prev[i]; j = next[j]) {
      const Vec2& q = p_[j];
      if (orient(a, b, q) >= 0 && orient(b, c, q) >= 0 && orient(c, a, q) >= 0) return false;
    }
    return true;
  };
  // Ears are clipped in rounds starting where the last one was cut, which
  // keeps the fan short and the cost near O(n^2) in the worst case.
  int remaining = n, i = 0, misses = 0;
  std::vector<std::array<int, 3>> tris;
  while (remaining > 3) {
    if (is_ear(i)) {
      tris.push_back({prev[i], i, next[i]});
      next[prev[i]] = next[i];
      prev[next[i]] = prev[i];
      --remaining;
      i = next[i];
      misses = 0;
    } else {
      i = next[i];
      if (++misses > remaining) throw Error("garment panel outline is not a simple polygon (no ear left to clip)");
    }
  }
  tris.push_back({prev[i], i, next[i]});
  // Neighbours through a map of directed edges.
  t_.clear();
  for (const auto& v : tris) t_.push_back({v, {-1, -1, -1}});
  std::vector<std::vector<std::pair<int, int>>> out_edges(n);  // from -> (to, tri)
  for (int t = 0; t < static_cast<int>(t_.size()); ++t)
    for (int k = 0; k < 3; ++k) out_edges[t_[t].v[(k + 1) % 3]].push_back({t_[t].v[(k + 2) % 3], t});
  for (int t = 0; t < static_cast<int>(t_.size()); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = t_[t].v[(k + 1) % 3], b = t_[t].v[(k + 2) % 3];
      for (const auto& [to, other] : out_edges[b])
        if (to == a) t_[t].n[k] = other;
    }
}

bool Triangulation::needs_flip(int tri, int k) const {
  const int u = t_[tri].n[k];
  if (u < 0) return false;
  const Tri& t = t_[tri];
  const int m = link_of(u, tri);
  const int d = t_[u].v[m];
  return incircle(p_[t.v[0]], p_[t.v[1]], p_[t.v[2]], p_[d]) > 0;
}

// Flips the edge opposite t.v[k]: (a, b, c) + (d, c, b) -> (a, b, d) + (a, d, c).
void Triangulation::flip(int tri, int k) {
  const int u = t_[tri].n[k];
  const int m = link_of(u, tri);
  const int a = t_[tri].v[k], b = t_[tri].v[(k + 1) % 3], c = t_[tri].v[(k + 2) % 3];
  const int d = t_[u].v[m];
  const int n_ca = t_[tri].n[(k + 1) % 3], n_ab = t_[tri].n[(k + 2) % 3];
  const int n_bd = t_[u].n[(m + 1) % 3], n_dc = t_[u].n[(m + 2) % 3];
  t_[tri] = {{a, b, d}, {n_bd, u, n_ab}};
  t_[u] = {{a, d, c}, {n_dc, n_ca, tri}};
  relink(n_bd, u, tri);
  relink(n_ca, tri, u);
}

void Triangulation::make_delaunay() {
  bool changed = true;
  for (int pass = 0; changed && pass < 1000; ++pass) {
    changed = false;
    for (int t = 0; t < static_cast<int>(t_.size()); ++t)
      for (int k = 0; k < 3; ++k)
        if (needs_flip(t, k)) {
          flip(t, k);
          changed = true;
        }
  }
}

void Triangulation::legalise(int tri, int point) {
  std::vector<int> stack{tri};
  int guard = 0;
  while (!stack.empty() && ++guard < 100000) {
    const int t = stack.back();
    stack.pop_back();
    const int k = slot_of(t, point);
    if (k < 0 || !needs_flip(t, k)) continue;
    const int u = t_[t].n[k];
    flip(t, k);  // t = (point, b, d), u = (point, d, c): both keep `point` first
    stack.push_back(t);
    stack.push_back(u);
  }
}

int Triangulation::locate(const Vec2& q) const {
  auto contains = [&](int t) {
    const Tri& tr = t_[t];
    return orient(p_[tr.v[0]], p_[tr.v[1]], q) > 0 && orient(p_[tr.v[1]], p_[tr.v[2]], q) > 0 &&
           orient(p_[tr.v[2]], p_[tr.v[0]], q) > 0;
  };
  int t = std::min(last_, static_cast<int>(t_.size()) - 1);
  for (int step = 0; step < 4 * static_cast<int>(t_.size()) + 16; ++step) {
    const Tri& tr = t_[t];
    int next = -2;
    for (int k = 0; k < 3; ++k)
      if (orient(p_[tr.v[(k + 1) % 3]], p_[tr.v[(k + 2) % 3]], q) < 0) {
        next = tr.n[k];
        break;
      }
    if (next == -2) return last_ = t;
    if (next < 0) break;  // blocked by the outline (concave panel): search all
    t = next;
  }
  for (int s = 0; s < static_cast<int>(t_.size()); ++s)
    if (contains(s)) return last_ = s;
  return -1;
}

bool Triangulation::insert(int point) {
  const int t = locate(p_[point]);
  if (t < 0) return false;  // on an edge or outside: left out
  const Tri old = t_[t];
  const int a = old.v[0], b = old.v[1], c = old.v[2];
  const int na = old.n[0], nb = old.n[1], nc = old.n[2];
  const int t1 = static_cast<int>(t_.size()), t2 = t1 + 1;
  t_[t] = {{a, b, point}, {t1, t2, nc}};
  t_.push_back({{b, c, point}, {t2, t, na}});
  t_.push_back({{c, a, point}, {t, t1, nb}});
  relink(na, t, t1);
  relink(nb, t, t2);
  legalise(t, point);
  legalise(t1, point);
  legalise(t2, point);
  return true;
}

void Triangulation::smooth(int num_boundary, int rounds, double min_area) {
  const int n = static_cast<int>(p_.size());
  for (int round = 0; round < rounds; ++round) {
    std::vector<std::vector<int>> around(n);  // triangles per vertex
    for (int t = 0; t < static_cast<int>(t_.size()); ++t)
      for (int v : t_[t].v) around[v].push_back(t);
    for (int v = num_boundary; v < n; ++v) {
      Vec2 sum = Vec2::Zero();
      int count = 0;
      for (int t : around[v])
        for (int w : t_[t].v)
          if (w != v) {
            sum += p_[w];
            ++count;
          }
      if (count == 0) continue;
      const Vec2 old = p_[v];
      p_[v] = sum / count;  // each neighbour counted twice: still the centroid
      for (int t : around[v]) {
        const Tri& tr = t_[t];
        if (orient(p_[tr.v[0]], p_[tr.v[1]], p_[tr.v[2]]) < 2 * min_area) {
          p_[v] = old;
          break;
        }
      }
    }
    make_delaunay();
  }
}

}  // namespace

double signed_area2(const std::vector<Vec2>& polygon) {
  double a = 0;
  for (std::size_t i = 0, j = polygon.size() - 1; i < polygon.size(); j = i++)
    a += polygon[j].x() * polygon[i].y() - polygon[i].x() * polygon[j].y();
  return a;
}

PlanarMesh mesh_polygon(const std::vector<Vec2>& outline, double h, int smoothing, double margin) {
  const int n = static_cast<int>(outline.size());
  if (n < 3) throw Error("garment panel outline has fewer than 3 points");
  if (!(h > 0)) throw Error("garment panel meshing needs a positive edge length");
  if (signed_area2(outline) <= 0) throw Error("garment panel outline is not counter-clockwise");
  PlanarMesh mesh;
  mesh.points = outline;
  mesh.num_boundary = n;

  // Lattice rows at h * sqrt(3) / 2, every other row shifted by h / 2.
  Vec2 lo = outline[0], hi = outline[0];
  for (const Vec2& q : outline) {
    lo = lo.cwiseMin(q);
    hi = hi.cwiseMax(q);
  }
  // Outline segments bucketed by cell for the distance test.
  const double cell = h;
  const int gx = std::max(1, static_cast<int>(std::ceil((hi.x() - lo.x()) / cell)) + 1);
  const int gy = std::max(1, static_cast<int>(std::ceil((hi.y() - lo.y()) / cell)) + 1);
  std::vector<std::vector<int>> buckets(static_cast<std::size_t>(gx) * gy);
  const double reach = margin * h;
  for (int i = 0; i < n; ++i) {
    const Vec2 &a = outline[i], &b = outline[(i + 1) % n];
    const int x0 = std::max(0, static_cast<int>((std::min(a.x(), b.x()) - reach - lo.x()) / cell));
    const int x1 = std::min(gx - 1, static_cast<int>((std::max(a.x(), b.x()) + reach - lo.x()) / cell));
    const int y0 = std::max(0, static_cast<int>((std::min(a.y(), b.y()) - reach - lo.y()) / cell));
    const int y1 = std::min(gy - 1, static_cast<int>((std::max(a.y(), b.y()) + reach - lo.y()) / cell));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) buckets[static_cast<std::size_t>(y) * gx + x].push_back(i);
  }
  auto near_outline = [&](const Vec2& q) {
    const int x = std::clamp(static_cast<int>((q.x() - lo.x()) / cell), 0, gx - 1);
    const int y = std::clamp(static_cast<int>((q.y() - lo.y()) / cell), 0, gy - 1);
    for (int i : buckets[static_cast<std::size_t>(y) * gx + x])
      if (segment_distance(q, outline[i], outline[(i + 1) % n]) < reach) return true;
    return false;
  };
  const double dy = h * std::sqrt(3.0) / 2.0;
  std::uint64_t id = 0;
  for (int row = 0; lo.y() + row * dy <= hi.y(); ++row) {
    const double y = lo.y() + (row + 0.5) * dy;
    const double shift = (row % 2) ? 0.5 * h : 0.0;
    for (double x = lo.x() + shift; x <= hi.x(); x += h, ++id) {
      const Vec2 q(x + 1e-3 * h * hash_unit(2 * id), y + 1e-3 * h * hash_unit(2 * id + 1));
      if (inside_polygon(q, outline) && !near_outline(q)) mesh.points.push_back(q);
    }
  }

  Triangulation tri(mesh.points);
  tri.ear_clip(n);
  tri.make_delaunay();
  std::vector<int> index(mesh.points.size(), -1);
  int kept = 0;
  for (int i = 0; i < static_cast<int>(mesh.points.size()); ++i)
    if (i < n || tri.insert(i)) index[i] = kept++;
  tri.smooth(n, smoothing, 0.05 * h * h);
  mesh.triangles = tri.triangles();
  // Drop points that could not be inserted (never used by a triangle).
  std::vector<Vec2> points(kept);
  for (std::size_t i = 0; i < index.size(); ++i)
    if (index[i] >= 0) points[index[i]] = mesh.points[i];
  for (auto& t : mesh.triangles)
    for (int& v : t) v = index[v];
  mesh.points = std::move(points);
  return mesh;
}

}  // namespace layers::garment
