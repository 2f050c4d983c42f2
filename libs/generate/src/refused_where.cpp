// The most stretched edges of a refused scene's frame (see refused_where.h).
#include "refused_where.h"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <utility>

namespace layers::generate {

namespace {

struct Edge {
  double stretch;
  std::size_t garment;
  int a, b;
};

std::vector<Edge> stretched_edges(const data::SequenceData& seq, int frame) {
  std::vector<Edge> edges;
  for (std::size_t g = 0; g < seq.garments.size(); ++g) {
    const data::GarmentData& garment = seq.garments[g];
    const std::size_t nv = static_cast<std::size_t>(garment.n_vertices());
    if (garment.positions.size() < (static_cast<std::size_t>(frame) + 1) * nv * 3) continue;
    const float* p = garment.positions.data() + static_cast<std::size_t>(frame) * nv * 3;
    std::set<std::pair<int, int>> seen;
    for (std::size_t f = 0; f + 2 < garment.faces.size(); f += 3)
      for (int k = 0; k < 3; ++k) {
        const int u = garment.faces[f + k], v = garment.faces[f + (k + 1) % 3];
        if (!seen.emplace(std::min(u, v), std::max(u, v)).second) continue;
        const auto at = [](const float* x, int i) { return Eigen::Vector3d(x[3 * i], x[3 * i + 1], x[3 * i + 2]); };
        const double rest = (at(garment.rest.data(), u) - at(garment.rest.data(), v)).norm();
        if (!(rest > 0)) continue;
        edges.push_back({(at(p, u) - at(p, v)).norm() / rest - 1.0, g, std::min(u, v), std::max(u, v)});
      }
  }
  return edges;
}

}  // namespace

int most_stretched_frame(const data::SequenceData& seq) {
  const int frames = static_cast<int>(seq.wind.strength.size());
  int best = 0;
  double worst = -1e30;
  for (int f = 0; f < frames; ++f)
    for (const Edge& e : stretched_edges(seq, f))
      if (e.stretch > worst) worst = e.stretch, best = f;
  return best;
}

std::vector<std::string> most_stretched_edges(const data::SequenceData& seq, int frame, int count) {
  std::vector<Edge> edges = stretched_edges(seq, frame);
  const std::size_t keep = std::min(edges.size(), static_cast<std::size_t>(std::max(count, 0)));
  std::partial_sort(edges.begin(), edges.begin() + static_cast<std::ptrdiff_t>(keep), edges.end(),
                    [](const Edge& x, const Edge& y) { return x.stretch > y.stretch; });
  const std::size_t nj = seq.body.joint_names.size();
  std::vector<std::string> out;
  for (std::size_t i = 0; i < keep; ++i) {
    const Edge& e = edges[i];
    const data::GarmentData& garment = seq.garments[e.garment];
    const float* p = garment.positions.data() + static_cast<std::size_t>(frame) * garment.n_vertices() * 3;
    const Eigen::Vector3d mid = 0.5 * (Eigen::Vector3d(p[3 * e.a], p[3 * e.a + 1], p[3 * e.a + 2]) +
                                       Eigen::Vector3d(p[3 * e.b], p[3 * e.b + 1], p[3 * e.b + 2]));
    std::string joint = "none";
    double best = 1e30;
    if (seq.body.joints.size() >= (static_cast<std::size_t>(frame) + 1) * nj * 12) {
      const float* m = seq.body.joints.data() + static_cast<std::size_t>(frame) * nj * 12;
      for (std::size_t j = 0; j < nj; ++j) {
        const Eigen::Vector3d t(m[j * 12 + 3], m[j * 12 + 7], m[j * 12 + 11]);
        if ((t - mid).norm() < best) best = (t - mid).norm(), joint = seq.body.joint_names[j];
      }
    }
    char line[256];
    std::snprintf(line, sizeof line, "%s: edge %d-%d stretched %.2f%% at (%.3f, %.3f, %.3f) m, nearest joint %s",
                  garment.name.c_str(), e.a, e.b, 100.0 * e.stretch, mid.x(), mid.y(), mid.z(), joint.c_str());
    out.emplace_back(line);
  }
  return out;
}

}  // namespace layers::generate
