// Body vertices near the garment, via a k-d tree (see body_contacts.h).
#include "body_contacts.h"

#include <unordered_map>
#include <vector>

#include <ATen/Parallel.h>

#include "layers/geometry/nearest.h"

namespace layers::layersnet {
namespace {

at::Tensor cpu_points(const at::Tensor& t) { return t.detach().to(at::kCPU, at::kFloat).contiguous(); }

Eigen::RowVector3f row(const float* p) { return Eigen::RowVector3f(p[0], p[1], p[2]); }

}  // namespace

BodyContacts find_body_contacts(const at::Tensor& body_next, const at::Tensor& centroids, const at::Tensor& vertices,
                                double radius, std::int64_t max_senders) {
  const at::Tensor body = cpu_points(body_next), cen = cpu_points(centroids), ver = cpu_points(vertices);
  const std::int64_t P = cen.size(0), V = ver.size(0);
  const std::int64_t K = radius > 0 ? max_senders : 0;
  const auto r = static_cast<float>(radius);

  // Body vertices inside the garment's box grown by the radius.
  at::Tensor kept = at::empty({0}, at::kLong);
  if (V > 0 && body.size(0) > 0 && radius > 0) {
    const at::Tensor lo = std::get<0>(ver.min(0)) - r, hi = std::get<0>(ver.max(0)) + r;
    kept = at::nonzero(((body >= lo) & (body <= hi)).all(1)).reshape({-1});
  }
  const at::Tensor kept_points = body.index_select(0, kept).contiguous();
  const std::int64_t* kept_id = kept.data_ptr<std::int64_t>();
  geometry::PointIndex tree;
  if (kept.numel() > 0)
    tree = geometry::PointIndex(Eigen::Map<const geometry::Points>(kept_points.data_ptr<float>(), kept.numel(), 3));

  // Senders per patch (tree rows), closest first.
  std::vector<std::vector<int>> found(P);
  if (K > 0 && tree.size() > 0) {
    const float* c = cen.data_ptr<float>();
    at::parallel_for(0, P, 16, [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t p = begin; p < end; ++p)
        for (const geometry::Neighbour& n : tree.knn(row(c + 3 * p), static_cast<int>(K)))
          if (n.index >= 0 && n.distance < r) found[p].push_back(n.index);
    });
  }
  BodyContacts out;
  out.slot = at::zeros({P, K}, at::kLong);
  out.slot_valid = at::zeros({P, K}, at::kBool);
  std::vector<std::int64_t> ids;
  std::unordered_map<int, std::int64_t> token_of;
  auto slot = out.slot.accessor<std::int64_t, 2>();
  auto valid = out.slot_valid.accessor<bool, 2>();
  for (std::int64_t p = 0; p < P; ++p) {
    for (std::size_t k = 0; k < found[p].size(); ++k) {
      auto [it, fresh] = token_of.emplace(found[p][k], static_cast<std::int64_t>(ids.size()));
      if (fresh) ids.push_back(kept_id[found[p][k]]);
      slot[p][static_cast<std::int64_t>(k)] = it->second;
      valid[p][static_cast<std::int64_t>(k)] = true;
    }
  }
  out.ids = at::tensor(ids, at::kLong).reshape({-1});

  // Nearest body vertex of every garment vertex.
  out.nearest = at::zeros({V}, at::kLong);
  out.nearest_valid = at::zeros({V}, at::kBool);
  if (tree.size() > 0) {
    const float* v = ver.data_ptr<float>();
    std::int64_t* nearest = out.nearest.data_ptr<std::int64_t>();
    bool* near = out.nearest_valid.data_ptr<bool>();
    at::parallel_for(0, V, 256, [&](std::int64_t begin, std::int64_t end) {
      for (std::int64_t i = begin; i < end; ++i) {
        const geometry::Neighbour n = tree.nearest(row(v + 3 * i));
        if (n.index >= 0 && n.distance < r) {
          nearest[i] = kept_id[n.index];
          near[i] = true;
        }
      }
    });
  }
  return out;
}

}  // namespace layers::layersnet
