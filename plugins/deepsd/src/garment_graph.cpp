// Mesh graph of a garment and the neighbour mean (see garment_graph.h).
#include "garment_graph.h"

#include <algorithm>
#include <utility>
#include <vector>

namespace layers::deepsd {

GarmentGraph mesh_graph(const at::Tensor& faces, std::int64_t vertices) {
  const at::Tensor f = faces.to(at::kCPU, at::kLong).contiguous();
  const std::int64_t* p = f.data_ptr<std::int64_t>();
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  edges.reserve(static_cast<std::size_t>(f.size(0)) * 6);
  for (std::int64_t i = 0; i < f.size(0); ++i) {
    for (int c = 0; c < 3; ++c) {
      const std::int64_t a = p[3 * i + c], b = p[3 * i + (c + 1) % 3];
      if (a == b) continue;
      edges.emplace_back(a, b);
      edges.emplace_back(b, a);
    }
  }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());

  const auto n = static_cast<std::int64_t>(edges.size());
  at::Tensor src = at::empty({n}, at::kLong), dst = at::empty({n}, at::kLong);
  std::vector<float> degree(static_cast<std::size_t>(vertices), 0.0f);
  for (std::int64_t e = 0; e < n; ++e) {
    src.data_ptr<std::int64_t>()[e] = edges[e].first;
    dst.data_ptr<std::int64_t>()[e] = edges[e].second;
    degree[static_cast<std::size_t>(edges[e].second)] += 1.0f;
  }
  for (float& d : degree) d = d > 0 ? 1.0f / d : 0.0f;

  GarmentGraph g;
  g.src = src.to(faces.device());
  g.dst = dst.to(faces.device());
  g.inv_degree = at::tensor(degree, at::kFloat).view({vertices, 1}).to(faces.device());
  g.vertices = vertices;
  return g;
}

at::Tensor mean_over_neighbours(const at::Tensor& h, const GarmentGraph& graph) {
  at::Tensor sum = at::zeros_like(h).index_add(0, graph.dst, h.index_select(0, graph.src));
  return sum * graph.inv_degree.to(h.scalar_type());
}

}  // namespace layers::deepsd
