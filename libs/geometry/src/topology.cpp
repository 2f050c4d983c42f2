// Unique edges and vertex adjacency (see topology.h).
#include "layers/geometry/topology.h"

#include <algorithm>
#include <utility>

namespace layers::geometry {

namespace {

// Every face's three edges as (min, max) pairs, sorted (an edge shared by
// two faces appears twice).
std::vector<std::pair<int, int>> sorted_face_edges(const Faces& faces) {
  std::vector<std::pair<int, int>> pairs;
  pairs.reserve(static_cast<std::size_t>(faces.rows()) * 3);
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      const int a = faces(f, c), b = faces(f, (c + 1) % 3);
      pairs.emplace_back(std::min(a, b), std::max(a, b));
    }
  }
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

}  // namespace

Edges unique_edges(const Faces& faces) {
  std::vector<std::pair<int, int>> pairs = sorted_face_edges(faces);
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  Edges out(static_cast<Eigen::Index>(pairs.size()), 2);
  for (std::size_t e = 0; e < pairs.size(); ++e) {
    out(static_cast<Eigen::Index>(e), 0) = pairs[e].first;
    out(static_cast<Eigen::Index>(e), 1) = pairs[e].second;
  }
  return out;
}

Eigen::VectorXd edge_lengths(const Points& points, const Edges& edges) {
  Eigen::VectorXd out(edges.rows());
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    out[e] = (points.row(edges(e, 0)).cast<double>() - points.row(edges(e, 1)).cast<double>()).norm();
  return out;
}

Edges boundary_edges(const Faces& faces) {
  const std::vector<std::pair<int, int>> pairs = sorted_face_edges(faces);
  std::vector<std::pair<int, int>> once;
  for (std::size_t i = 0; i < pairs.size();) {
    std::size_t j = i;
    while (j < pairs.size() && pairs[j] == pairs[i]) ++j;
    if (j - i == 1) once.push_back(pairs[i]);
    i = j;
  }
  Edges out(static_cast<Eigen::Index>(once.size()), 2);
  for (std::size_t e = 0; e < once.size(); ++e) {
    out(static_cast<Eigen::Index>(e), 0) = once[e].first;
    out(static_cast<Eigen::Index>(e), 1) = once[e].second;
  }
  return out;
}

std::vector<char> boundary_vertices(const Faces& faces, int num_vertices) {
  const Edges edges = boundary_edges(faces);
  std::vector<char> out(static_cast<std::size_t>(num_vertices), 0);
  for (Eigen::Index e = 0; e < edges.rows(); ++e)
    out.at(static_cast<std::size_t>(edges(e, 0))) = out.at(static_cast<std::size_t>(edges(e, 1))) = 1;
  return out;
}

Adjacency vertex_adjacency(const Edges& edges, int num_vertices) {
  Adjacency adj;
  adj.offsets.assign(static_cast<std::size_t>(num_vertices) + 1, 0);
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    ++adj.offsets[edges(e, 0) + 1];
    ++adj.offsets[edges(e, 1) + 1];
  }
  for (int v = 0; v < num_vertices; ++v) adj.offsets[v + 1] += adj.offsets[v];
  adj.neighbours.resize(static_cast<std::size_t>(adj.offsets.back()));
  std::vector<int> fill(adj.offsets.begin(), adj.offsets.end() - 1);
  for (Eigen::Index e = 0; e < edges.rows(); ++e) {
    int a = edges(e, 0), b = edges(e, 1);
    adj.neighbours[fill[a]++] = b;
    adj.neighbours[fill[b]++] = a;
  }
  for (int v = 0; v < num_vertices; ++v) {
    std::sort(adj.neighbours.begin() + adj.offsets[v], adj.neighbours.begin() + adj.offsets[v + 1]);
  }
  return adj;
}

Adjacency vertex_adjacency(const Faces& faces, int num_vertices) {
  return vertex_adjacency(unique_edges(faces), num_vertices);
}

}  // namespace layers::geometry
