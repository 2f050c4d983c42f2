// garment_pattern.cpp -- from placed panel grids to one sewn garment mesh:
// outward orientation of each flattened panel, outline sampling with
// matched seam counts, planar meshing, lifting onto the 3D grid surface,
// seam merging and the UV atlas.
#include "layers/garment/garment_pattern.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <string>

#include "layers/core/error.h"
#include "layers/garment/garment_triangulate.h"
#include "layers/geometry/topology.h"

namespace layers::garment {
namespace {

double cross2(const Vec2& a, const Vec2& b) { return a.x() * b.y() - a.y() * b.x(); }

// Maps points of a developed grid back onto its 3D surface: the grid cells,
// split into two triangles each, bucketed in UV.
class Lifter {
 public:
  Lifter(const PanelGrid& g, const std::vector<Vec2>& uv) : g_(g), uv_(uv) {
    lo_ = hi_ = uv[0];
    for (const Vec2& q : uv) {
      lo_ = lo_.cwiseMin(q);
      hi_ = hi_.cwiseMax(q);
    }
    double mean_cell = 0;
    for (int i = 0; i + 1 < g.rows; ++i) mean_cell += (uv[idx(i + 1, 0)] - uv[idx(i, 0)]).norm();
    cell_ = std::max(1e-3, 2.0 * mean_cell / std::max(1, g.rows - 1));
    nx_ = std::max(1, static_cast<int>((hi_.x() - lo_.x()) / cell_) + 1);
    ny_ = std::max(1, static_cast<int>((hi_.y() - lo_.y()) / cell_) + 1);
    buckets_.resize(static_cast<std::size_t>(nx_) * ny_);
    for (int i = 0; i + 1 < g.rows; ++i)
      for (int j = 0; j + 1 < g.cols; ++j)
        for (int half = 0; half < 2; ++half) {
          const auto t = tri(i, j, half);
          Vec2 a = uv[t[0]], b = a;
          for (int k : t) {
            a = a.cwiseMin(uv[k]);
            b = b.cwiseMax(uv[k]);
          }
          const int x0 = bx(a.x()), x1 = bx(b.x()), y0 = by(a.y()), y1 = by(b.y());
          const int id = 2 * (i * (g.cols - 1) + j) + half;
          for (int y = y0; y <= y1; ++y)
            for (int x = x0; x <= x1; ++x) buckets_[static_cast<std::size_t>(y) * nx_ + x].push_back(id);
        }
  }

  body::Vec3 lift(const Vec2& q) const {
    double best = -std::numeric_limits<double>::infinity();
    body::Vec3 best_point = body::Vec3::Zero();
    for (int id : buckets_[static_cast<std::size_t>(by(q.y())) * nx_ + bx(q.x())]) {
      const int cell = id / 2, half = id % 2;
      const auto t = tri(cell / (g_.cols - 1), cell % (g_.cols - 1), half);
      const Vec2 &a = uv_[t[0]], &b = uv_[t[1]], &c = uv_[t[2]];
      const double area = cross2(b - a, c - a);
      if (std::abs(area) < 1e-18) continue;
      const double wa = cross2(b - q, c - q) / area, wb = cross2(c - q, a - q) / area, wc = 1.0 - wa - wb;
      const double worst = std::min({wa, wb, wc});
      if (worst > best) {  // inside when worst >= 0; else the least-outside triangle
        best = worst;
        best_point = wa * point(t[0]) + wb * point(t[1]) + wc * point(t[2]);
        if (worst >= 0) break;
      }
    }
    if (best == -std::numeric_limits<double>::infinity())
      throw Error("garment panel '" + g_.name + "': point outside its grid");
    return best_point;
  }

 private:
  int idx(int i, int j) const { return i * g_.cols + j; }
  std::array<int, 3> tri(int i, int j, int half) const {
    return half == 0 ? std::array<int, 3>{idx(i, j), idx(i, j + 1), idx(i + 1, j + 1)}
                     : std::array<int, 3>{idx(i, j), idx(i + 1, j + 1), idx(i + 1, j)};
  }
  const body::Vec3& point(int k) const { return g_.points[k]; }
  int bx(double x) const { return std::clamp(static_cast<int>((x - lo_.x()) / cell_), 0, nx_ - 1); }
  int by(double y) const { return std::clamp(static_cast<int>((y - lo_.y()) / cell_), 0, ny_ - 1); }

  const PanelGrid& g_;
  const std::vector<Vec2>& uv_;
  Vec2 lo_, hi_;
  double cell_ = 1;
  int nx_ = 1, ny_ = 1;
  std::vector<std::vector<int>> buckets_;
};

// Position of a side point along the outline walk: bottom (j up), right
// (i up), top (j down), left (i down); from 0 to 2J + 2I.
struct Walk {
  int I, J;  // segments per column / per row
  int pos(Side s, int k) const {
    switch (s) {
      case Side::Bottom:
        return k;
      case Side::Right:
        return J + k;
      case Side::Top:
        return J + I + (J - k);
      default:
        return 2 * J + I + (I - k);
    }
  }
  std::pair<int, int> cell(int w) const {  // (i, j) of walk position w
    if (w <= J) return {0, w};
    if (w <= J + I) return {w - J, J};
    if (w <= 2 * J + I) return {I, J - (w - J - I)};
    return {I - (w - 2 * J - I), 0};
  }
  int side_length(Side s) const { return (s == Side::Bottom || s == Side::Top) ? J : I; }
};

struct EdgeSamples {
  int panel = 0, w0 = 0, w1 = 0;  // walk interval
  bool reversed = false;          // `from` is at w1
  std::vector<body::Vec3> line3;  // grid points in walk order
  std::vector<Vec2> line2;
  double length = 0;
  int segments = 1;
  std::vector<int> outline;  // outline index of each walk-order sample (segments + 1)
  int index(int k) const { return outline[reversed ? segments - k : k]; }
};

std::vector<double> cumulative(const std::vector<body::Vec3>& line) {
  std::vector<double> s(line.size(), 0.0);
  for (std::size_t i = 1; i < line.size(); ++i) s[i] = s[i - 1] + (line[i] - line[i - 1]).norm();
  return s;
}

// Point at arc length t along a polyline with cumulative lengths s.
template <class P>
P along(const std::vector<P>& line, const std::vector<double>& s, double t) {
  if (t <= 0) return line.front();
  if (t >= s.back()) return line.back();
  const auto it = std::upper_bound(s.begin(), s.end(), t);
  const std::size_t k = static_cast<std::size_t>(it - s.begin());
  const double len = s[k] - s[k - 1];
  const double f = len > 0 ? (t - s[k - 1]) / len : 0.0;
  return line[k - 1] + f * (line[k] - line[k - 1]);
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  }
  void join(int a, int b) { parent[find(a)] = find(b); }
};

const char* side_name(Side s) {
  switch (s) {
    case Side::Bottom:
      return "bottom";
    case Side::Right:
      return "right";
    case Side::Top:
      return "top";
    default:
      return "left";
  }
}

}  // namespace

double GarmentMesh::style_value(const std::string& key) const {
  for (const auto& [k, v] : style)
    if (k == key) return v;
  return std::numeric_limits<double>::quiet_NaN();
}

namespace {

// A panel's UVs, mirrored when needed so that counter-clockwise cells in
// UV face away from the body in 3D (their 3D normal is
// (P[i][j+1] - P) x (P[i+1][j] - P)).
std::vector<Vec2> flat_panel(const PanelGrid& g, const geometry::PointIndex& body) {
  std::vector<Vec2> uv = develop(g);
  double outward = 0;
  for (int i = 0; i + 1 < g.rows; ++i)
    for (int j = 0; j + 1 < g.cols; ++j) {
      const body::Vec3 n = (g.at(i, j + 1) - g.at(i, j)).cross(g.at(i + 1, j) - g.at(i, j));
      const body::Vec3 centre = 0.25 * (g.at(i, j) + g.at(i + 1, j) + g.at(i, j + 1) + g.at(i + 1, j + 1));
      const auto near = body.nearest(centre.cast<float>().transpose());
      if (near.index < 0) continue;
      outward += n.dot(centre - body.points().row(near.index).transpose().cast<double>());
    }
  if (outward < 0)
    for (Vec2& q : uv) q.x() = -q.x();
  return uv;
}

// The grid polyline (3D and UV) of an edge, in walk order.
EdgeSamples edge_samples(const Pattern& pattern, const std::vector<Walk>& walks,
                         const std::vector<std::vector<Vec2>>& uvs, const Edge& e) {
  const int np = static_cast<int>(pattern.panels.size());
  if (e.panel < 0 || e.panel >= np) throw Error("garment pattern: edge on a missing panel");
  const Walk& w = walks[e.panel];
  const PanelGrid& g = pattern.panels[e.panel];
  if (e.from == e.to || std::min(e.from, e.to) < 0 || std::max(e.from, e.to) > w.side_length(e.side))
    throw Error("garment panel '" + g.name + "': bad edge on its " + side_name(e.side) + " side");
  EdgeSamples s;
  s.panel = e.panel;
  const int a = w.pos(e.side, e.from), b = w.pos(e.side, e.to);
  s.w0 = std::min(a, b);
  s.w1 = std::max(a, b);
  s.reversed = a > b;
  for (int k = s.w0; k <= s.w1; ++k) {
    const auto [i, j] = w.cell(k);
    s.line3.push_back(g.at(i, j));
    s.line2.push_back(uvs[e.panel][i * g.cols + j]);
  }
  s.length = cumulative(s.line3).back();
  return s;
}

// One meshed panel: points (outline first) in UV and 3D, CCW triangles.
struct PanelMesh {
  std::vector<Vec2> uv;
  std::vector<body::Vec3> xyz;
  std::vector<std::array<int, 3>> triangles;
};

// Samples the outline of panel `g` along its edges (sorted by walk
// position and covering it exactly once), meshes the flat panel and lifts
// the interior points onto the grid's 3D surface. Records in every edge
// the outline index of each of its samples.
PanelMesh mesh_panel(const PanelGrid& g, const Walk& walk, const std::vector<Vec2>& uv,
                     const std::vector<EdgeSamples*>& mine, double h) {
  int expect = 0;
  for (const EdgeSamples* e : mine) {
    if (e->w0 != expect)
      throw Error("garment panel '" + g.name + "': outline not covered exactly once near walk position " +
                  std::to_string(expect));
    expect = e->w1;
  }
  if (expect != 2 * walk.I + 2 * walk.J) throw Error("garment panel '" + g.name + "': outline not closed by its edges");

  // Outline samples, uniform in 3D arc length along each edge.
  std::vector<Vec2> outline2;
  std::vector<body::Vec3> outline3;
  for (EdgeSamples* s : mine) {
    const std::vector<double> c3 = cumulative(s->line3);
    s->outline.clear();
    for (int k = 0; k < s->segments; ++k) {
      const double t = c3.back() * k / s->segments;
      s->outline.push_back(static_cast<int>(outline2.size()));
      outline3.push_back(along(s->line3, c3, t));
      outline2.push_back(along(s->line2, c3, t));
    }
    s->outline.push_back(s == mine.back() ? 0 : static_cast<int>(outline2.size()));  // the next edge's first
  }
  const int nb = static_cast<int>(outline2.size());
  // Mesh counter-clockwise in UV (a mirrored panel walks clockwise).
  const bool clockwise = signed_area2(outline2) < 0;
  std::vector<Vec2> ccw = outline2;
  if (clockwise) std::reverse(ccw.begin(), ccw.end());
  PlanarMesh pm;
  try {
    pm = mesh_polygon(ccw, h);
  } catch (const Error& e) {
    throw Error("garment panel '" + g.name + "': " + e.what());
  }
  auto local = [&](int k) { return k < nb && clockwise ? nb - 1 - k : k; };
  const Lifter lifter(g, uv);
  PanelMesh out;
  out.uv.resize(pm.points.size());
  out.xyz.resize(pm.points.size());
  for (int k = 0; k < static_cast<int>(pm.points.size()); ++k) {
    out.uv[local(k)] = pm.points[k];
    out.xyz[local(k)] = local(k) < nb ? outline3[local(k)] : lifter.lift(pm.points[k]);
  }
  for (const auto& t : pm.triangles) out.triangles.push_back({local(t[0]), local(t[1]), local(t[2])});
  return out;
}

}  // namespace

GarmentMesh sew(const Pattern& pattern, double h, const geometry::PointIndex& body) {
  const int np = static_cast<int>(pattern.panels.size());
  std::vector<std::vector<Vec2>> uvs(np);
  std::vector<Walk> walks(np);
  for (int p = 0; p < np; ++p) {
    const PanelGrid& g = pattern.panels[p];
    if (g.rows < 2 || g.cols < 2) throw Error("garment panel '" + g.name + "' has fewer than 2 rows or columns");
    walks[p] = {g.rows - 1, g.cols - 1};
    uvs[p] = flat_panel(g, body);
  }

  // Edges, with the sample count of a seam shared by both sides.
  std::vector<EdgeSamples> edges;
  std::vector<std::pair<int, int>> seam_edges;
  for (const Seam& seam : pattern.seams) {
    edges.push_back(edge_samples(pattern, walks, uvs, seam.a));
    edges.push_back(edge_samples(pattern, walks, uvs, seam.b));
    const int a = static_cast<int>(edges.size()) - 2, b = a + 1;
    edges[a].segments = edges[b].segments =
        std::max(1, static_cast<int>(std::lround(std::max(edges[a].length, edges[b].length) / h)));
    seam_edges.push_back({a, b});
  }
  for (const Edge& e : pattern.openings) {
    edges.push_back(edge_samples(pattern, walks, uvs, e));
    edges.back().segments = std::max(1, static_cast<int>(std::lround(edges.back().length / h)));
  }

  // Mesh the panels; lay their UV charts side by side along u.
  GarmentMesh out;
  std::vector<body::Vec3> points3;  // every panel's points, panel after panel
  std::vector<Vec2> points2;
  std::vector<std::array<int, 3>> tris;
  std::vector<int> tri_panel, panel_offset(np, 0);
  double atlas_x = 0;
  for (int p = 0; p < np; ++p) {
    std::vector<EdgeSamples*> mine;
    for (EdgeSamples& e : edges)
      if (e.panel == p) mine.push_back(&e);
    std::sort(mine.begin(), mine.end(), [](const EdgeSamples* a, const EdgeSamples* b) { return a->w0 < b->w0; });
    const PanelMesh m = mesh_panel(pattern.panels[p], walks[p], uvs[p], mine, h);
    out.panel_names.push_back(pattern.panels[p].name);
    panel_offset[p] = static_cast<int>(points3.size());
    Vec2 lo = m.uv[0], hi = m.uv[0];
    for (const Vec2& q : m.uv) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    const Vec2 shift(atlas_x - lo.x(), -lo.y());
    atlas_x += (hi.x() - lo.x()) + 0.05;
    for (const Vec2& q : m.uv) points2.push_back(q + shift);
    points3.insert(points3.end(), m.xyz.begin(), m.xyz.end());
    for (const auto& t : m.triangles) {
      tris.push_back({panel_offset[p] + t[0], panel_offset[p] + t[1], panel_offset[p] + t[2]});
      tri_panel.push_back(p);
    }
  }

  // Stitch: union of seam samples, positions averaged.
  UnionFind uf(static_cast<int>(points3.size()));
  for (const auto& [a, b] : seam_edges)
    for (int k = 0; k <= edges[a].segments; ++k)
      uf.join(panel_offset[edges[a].panel] + edges[a].index(k), panel_offset[edges[b].panel] + edges[b].index(k));
  std::vector<int> vertex_of(points3.size(), -1);
  std::vector<body::Vec3> sum;
  std::vector<int> count;
  for (std::size_t i = 0; i < points3.size(); ++i) {
    const int r = uf.find(static_cast<int>(i));
    if (vertex_of[r] < 0) {
      vertex_of[r] = static_cast<int>(sum.size());
      sum.push_back(body::Vec3::Zero());
      count.push_back(0);
    }
    vertex_of[i] = vertex_of[r];
    sum[vertex_of[i]] += points3[i];
    ++count[vertex_of[i]];
  }
  out.vertices.resize(static_cast<Eigen::Index>(sum.size()), 3);
  for (std::size_t v = 0; v < sum.size(); ++v) out.vertices.row(v) = (sum[v] / count[v]).cast<float>().transpose();
  out.uv.resize(static_cast<Eigen::Index>(points2.size()), 2);
  for (std::size_t i = 0; i < points2.size(); ++i) out.uv.row(i) = points2[i].cast<float>().transpose();
  out.faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  out.uv_faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  out.panel.resize(static_cast<Eigen::Index>(tris.size()));
  for (std::size_t f = 0; f < tris.size(); ++f) {
    for (int k = 0; k < 3; ++k) {
      out.uv_faces(f, k) = tris[f][k];
      out.faces(f, k) = vertex_of[tris[f][k]];
    }
    if (out.faces(f, 0) == out.faces(f, 1) || out.faces(f, 1) == out.faces(f, 2) || out.faces(f, 0) == out.faces(f, 2))
      throw Error("garment panel '" + pattern.panels[tri_panel[f]].name + "': a seam collapses a triangle");
    out.panel[f] = tri_panel[f];
  }
  repair_slivers(out);
  // Openings: edges used by a single face.
  const std::vector<char> open = geometry::boundary_vertices(out.faces, static_cast<int>(sum.size()));
  out.boundary.assign(open.begin(), open.end());
  return out;
}

}  // namespace layers::garment
