// Nearest body vertex per garment vertex through layers::geometry's k-d
// tree (see body_seeds.h).
#include "layers/mgnet/body_seeds.h"

#include "layers/geometry/nearest.h"

namespace layers::mgnet {
namespace {

geometry::Points to_points(const at::Tensor& x) {
  const at::Tensor cpu = x.detach().to(at::kCPU, at::kFloat).contiguous();
  return Eigen::Map<const geometry::Points>(cpu.data_ptr<float>(), cpu.size(0), 3);
}

}  // namespace

at::Tensor nearest_body_vertex(const at::Tensor& body, const at::Tensor& points) {
  const geometry::PointIndex index(to_points(body));
  const Eigen::VectorXi nearest = index.nearest_all(to_points(points));
  at::Tensor out = at::empty({points.size(0)}, at::kLong);
  auto a = out.accessor<std::int64_t, 1>();
  for (Eigen::Index i = 0; i < nearest.size(); ++i) a[i] = nearest[i] < 0 ? 0 : nearest[i];
  return out.to(points.device());
}

}  // namespace layers::mgnet
