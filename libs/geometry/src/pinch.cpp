// Pinch zones of a posed body (see pinch.h).
#include "layers/geometry/pinch.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <queue>
#include <utility>

#include "layers/geometry/nearest.h"
#include "layers/geometry/topology.h"

namespace layers::geometry {

std::vector<char> pinch_faces(const TriMesh& body, const std::vector<char>& crossing, double distance,
                              const std::vector<char>* examine) {
  const int nv = body.num_vertices(), nf = body.num_faces();
  std::vector<char> out(static_cast<std::size_t>(nf), 0);
  if (nf == 0) return out;
  if (!crossing.empty()) out = grow_faces(body, crossing, 1);
  if (!(distance > 0) || !body.vertices.allFinite()) return out;

  // For each vertex, the vertices within `distance` in space; a search
  // along the edges (Dijkstra, cut at kPinchDetour x distance) looks for
  // each of them, and a vertex it does not reach is on another part.
  const Adjacency adjacency = vertex_adjacency(body.faces, nv);
  const PointIndex index(body.vertices);
  const double reach = kPinchDetour * distance;
  constexpr double kUnseen = std::numeric_limits<double>::infinity();
  std::vector<double> along(static_cast<std::size_t>(nv), kUnseen);
  std::vector<int> touched;
  std::vector<std::uint32_t> wanted(static_cast<std::size_t>(nv), 0);
  std::uint32_t stamp = 0;
  using Item = std::pair<double, int>;
  std::priority_queue<Item, std::vector<Item>, std::greater<Item>> queue;
  std::vector<char> pinched(static_cast<std::size_t>(nv), 0);
  const auto point = [&](int i) { return body.vertices.row(i).cast<double>(); };
  for (int v = 0; v < nv; ++v) {
    if (examine != nullptr && !(*examine)[v]) continue;
    const std::vector<Neighbour> near = index.within(body.vertices.row(v), static_cast<float>(distance));
    ++stamp;
    int left = 0;
    for (const Neighbour& n : near) {
      if (n.index < 0 || n.index == v) continue;
      wanted[n.index] = stamp;
      ++left;
    }
    if (left == 0) continue;
    for (int i : touched) along[i] = kUnseen;
    touched.clear();
    queue = {};
    along[v] = 0;
    touched.push_back(v);
    queue.push({0.0, v});
    while (!queue.empty() && left > 0) {
      const auto [d, u] = queue.top();
      queue.pop();
      if (d > along[u]) continue;
      if (wanted[u] == stamp) {
        wanted[u] = 0;
        --left;
      }
      for (const int* w = adjacency.begin(u); w != adjacency.end(u); ++w) {
        const double dw = d + (point(*w) - point(u)).norm();
        if (dw > reach || dw >= along[*w]) continue;
        if (along[*w] == kUnseen) touched.push_back(*w);
        along[*w] = dw;
        queue.push({dw, *w});
      }
    }
    pinched[v] = left > 0 ? 1 : 0;
  }
  for (int f = 0; f < nf; ++f) {
    for (int k = 0; k < 3; ++k) out[f] = out[f] || pinched[body.faces(f, k)];
  }
  return out;
}

PinchZones pinch_zones_under(const TriMesh& body, const std::vector<char>& crossing, double distance,
                             const Points& cloth, double longest_edge) {
  PinchZones out;
  out.covered.assign(static_cast<std::size_t>(body.num_vertices()), 0);
  if (cloth.rows() > 0) {
    const PointIndex index(cloth);
    const double reach = 2 * std::max(distance, 0.0) + 0.5 * longest_edge;
    for (int v = 0; v < body.num_vertices(); ++v)
      out.covered[v] = index.nearest(body.vertices.row(v)).distance <= reach ? 1 : 0;
  }
  out.faces = pinch_faces(body, crossing, distance, &out.covered);
  return out;
}

PinchZones pinch_zones_under(const TriMesh& body, const std::vector<char>& crossing, double distance,
                             const std::vector<TriMesh>& cloth) {
  Eigen::Index rows = 0;
  for (const TriMesh& m : cloth) rows += m.num_vertices();
  Points points(rows, 3);
  double longest = 0;
  rows = 0;
  for (const TriMesh& m : cloth) {
    if (m.num_vertices() == 0) continue;
    points.middleRows(rows, m.num_vertices()) = m.vertices;
    rows += m.num_vertices();
    for (int f = 0; f < m.num_faces(); ++f)
      for (int k = 0; k < 3; ++k)
        longest = std::max(longest, (m.vertices.row(m.faces(f, k)).cast<double>() -
                                     m.vertices.row(m.faces(f, (k + 1) % 3)).cast<double>())
                                        .norm());
  }
  return pinch_zones_under(body, crossing, distance, points, longest);
}

}  // namespace layers::geometry
