// garment_fixture.h -- shared helpers for the garment template tests: two
// T-pose bodies from the shared assets (built once per process), a cache
// of built garments, and mesh inspection (topology, orientation, edge
// lengths, UV charts, boundary loops, contact with a surface).
#pragma once

#include <algorithm>
#include <array>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <string>
#include <tuple>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/garment/garment.h"
#include "layers/geometry/normals.h"
#include "layers/geometry/penetration.h"

namespace layers::garment::test {

// Shape 0: the average body; shape 1: a taller, heavier male.
inline body::ShapeParams test_shape(int which) {
  body::ShapeParams s;
  if (which == 1) {
    s.gender = 1.0;
    s.weight = 0.75;
    s.muscle = 0.6;
    s.height = 0.65;
  }
  return s;
}

inline const TPoseBody& tpose(int which) {
  static std::map<int, TPoseBody> cache;
  auto it = cache.find(which);
  if (it == cache.end())
    it = cache.emplace(which, t_pose_body(body::BodyModel::load()->build(test_shape(which)))).first;
  return it->second;
}

inline const geometry::Surface& skin(int which) {
  static std::map<int, geometry::Surface> cache;
  auto it = cache.find(which);
  if (it == cache.end()) it = cache.emplace(which, geometry::Surface::from_mesh(tpose(which).mesh)).first;
  return it->second;
}

inline GarmentParams params_at(double h) {
  GarmentParams p;
  p.edge_length = h;
  return p;
}

// One garment on its own, built once per process.
inline const GarmentMesh& garment(const std::string& type, int shape, std::uint64_t seed, double h = 0.02) {
  static std::map<std::tuple<std::string, int, std::uint64_t, double>, GarmentMesh> cache;
  const auto key = std::make_tuple(type, shape, seed, h);
  auto it = cache.find(key);
  if (it == cache.end()) it = cache.emplace(key, build_garment(type, tpose(shape), params_at(h), seed)).first;
  return it->second;
}

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(n) { std::iota(parent.begin(), parent.end(), 0); }
  int find(int x) { return parent[x] == x ? x : parent[x] = find(parent[x]); }
  void join(int a, int b) { parent[find(a)] = find(b); }
  int count() {
    std::set<int> roots;
    for (int i = 0; i < static_cast<int>(parent.size()); ++i) roots.insert(find(i));
    return static_cast<int>(roots.size());
  }
};

struct MeshReport {
  int over_shared_edges = 0;  // edges in more than two faces
  int misoriented_edges = 0;  // interior edges not traversed once each way
  int components = 0;
  int boundary_loops = 0;
  int boundary_flag_mismatch = 0;
  double edges_in_band = 0;    // share of edges within [0.6, 1.5] x h
  double outward = 0;          // share of faces whose normal points away from the nearest skin vertex
  double uv_area_ratio = 0;    // sum of UV areas / sum of 3D areas
  int uv_flipped = 0;          // UV triangles not counter-clockwise
  std::vector<int> uv_charts;  // connected UV pieces per panel
  int uv_shared_across_panels = 0;
};

inline MeshReport inspect(const GarmentMesh& g, const geometry::Surface& body, double h) {
  MeshReport r;
  std::map<std::pair<int, int>, int> undirected, directed;
  for (int f = 0; f < g.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = g.faces(f, k), b = g.faces(f, (k + 1) % 3);
      ++undirected[{std::min(a, b), std::max(a, b)}];
      ++directed[{a, b}];
    }
  UnionFind parts(g.num_vertices()), loops(g.num_vertices());
  std::vector<char> on_boundary(g.num_vertices(), 0);
  int in_band = 0;
  for (const auto& [e, n] : undirected) {
    r.over_shared_edges += n > 2;
    if (n == 2 && (directed[{e.first, e.second}] != 1 || directed[{e.second, e.first}] != 1)) ++r.misoriented_edges;
    parts.join(e.first, e.second);
    if (n == 1) {
      loops.join(e.first, e.second);
      on_boundary[e.first] = on_boundary[e.second] = 1;
    }
    const double len = (g.vertices.row(e.first) - g.vertices.row(e.second)).norm() / h;
    in_band += len >= 0.6 && len <= 1.5;
  }
  r.edges_in_band = static_cast<double>(in_band) / undirected.size();
  r.components = parts.count();
  std::set<int> loop_roots;
  for (int v = 0; v < g.num_vertices(); ++v) {
    if (on_boundary[v]) loop_roots.insert(loops.find(v));
    r.boundary_flag_mismatch += (on_boundary[v] != 0) != (g.boundary[v] != 0);
  }
  r.boundary_loops = static_cast<int>(loop_roots.size());

  const geometry::Points normals = geometry::face_normals(g.vertices, g.faces);
  int out = 0;
  double area3 = 0, area2 = 0;
  for (int f = 0; f < g.num_faces(); ++f) {
    const Eigen::RowVector3f c =
        (g.vertices.row(g.faces(f, 0)) + g.vertices.row(g.faces(f, 1)) + g.vertices.row(g.faces(f, 2))) / 3;
    const auto near = body.index().nearest(c);
    out += (c - body.vertices().row(near.index)).dot(normals.row(f)) > 0;
    const Eigen::RowVector3f a = g.vertices.row(g.faces(f, 0)), b = g.vertices.row(g.faces(f, 1)),
                             d = g.vertices.row(g.faces(f, 2));
    area3 += 0.5 * (b - a).cross(d - a).norm();
    const Eigen::RowVector2f p = g.uv.row(g.uv_faces(f, 0)), q = g.uv.row(g.uv_faces(f, 1)),
                             s = g.uv.row(g.uv_faces(f, 2));
    const double uv = 0.5 * ((q - p).x() * (s - p).y() - (q - p).y() * (s - p).x());
    area2 += uv;
    r.uv_flipped += uv <= 0;
  }
  r.outward = static_cast<double>(out) / g.num_faces();
  r.uv_area_ratio = area2 / area3;

  UnionFind charts(static_cast<int>(g.uv.rows()));
  std::vector<int> panel_of_uv(g.uv.rows(), -1);
  for (int f = 0; f < g.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int u = g.uv_faces(f, k);
      if (panel_of_uv[u] >= 0 && panel_of_uv[u] != g.panel[f]) ++r.uv_shared_across_panels;
      panel_of_uv[u] = g.panel[f];
      charts.join(u, g.uv_faces(f, (k + 1) % 3));
    }
  r.uv_charts.assign(g.panel_names.size(), 0);
  std::set<int> seen;
  for (int f = 0; f < g.num_faces(); ++f) {
    const int root = charts.find(g.uv_faces(f, 0));
    if (seen.insert(root).second) ++r.uv_charts[g.panel[f]];
  }
  return r;
}

}  // namespace layers::garment::test
