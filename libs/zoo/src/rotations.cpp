// Quaternion helpers shared by the model plugins (see rotations.h).
#include "layers/zoo/rotations.h"

#include <vector>

namespace layers::zoo {
namespace {

at::Tensor normalized(const at::Tensor& q) { return q / q.norm(2, {-1}, /*keepdim=*/true).clamp_min(1e-12); }

// The components w, x, y, z of [...,4] quaternions, each [...].
struct Parts {
  at::Tensor w, x, y, z;
  explicit Parts(const at::Tensor& q)
      : w(q.select(-1, 0)), x(q.select(-1, 1)), y(q.select(-1, 2)), z(q.select(-1, 3)) {}
};

// Leading dimensions of [...,4] followed by `tail`.
std::vector<std::int64_t> leading(const at::Tensor& q, std::initializer_list<std::int64_t> tail) {
  std::vector<std::int64_t> sizes(q.sizes().begin(), q.sizes().end() - 1);
  sizes.insert(sizes.end(), tail);
  return sizes;
}

}  // namespace

at::Tensor rotation_matrices(const at::Tensor& quaternions) {
  const Parts p(normalized(quaternions));
  const at::Tensor &w = p.w, &x = p.x, &y = p.y, &z = p.z;
  const at::Tensor rows = at::stack(
      {1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y), 2 * (x * y + w * z), 1 - 2 * (x * x + z * z),
       2 * (y * z - w * x), 2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)},
      -1);
  return rows.view(leading(quaternions, {3, 3}));
}

at::Tensor rotate_z(const at::Tensor& quaternions) { return rotation_matrices(quaternions).select(-1, 2); }

at::Tensor heading_quaternions(const at::Tensor& quaternions) {
  const at::Tensor forward = rotate_z(quaternions);
  const at::Tensor half = 0.5 * at::atan2(forward.select(-1, 0), forward.select(-1, 2));  // atan2(0, 0) = 0
  const at::Tensor zero = at::zeros_like(half);
  return at::stack({at::cos(half), zero, at::sin(half), zero}, -1);
}

at::Tensor quaternion_multiply(const at::Tensor& a, const at::Tensor& b) {
  const Parts p(a), q(b);
  return at::stack({p.w * q.w - p.x * q.x - p.y * q.y - p.z * q.z, p.w * q.x + p.x * q.w + p.y * q.z - p.z * q.y,
                    p.w * q.y - p.x * q.z + p.y * q.w + p.z * q.x, p.w * q.z + p.x * q.y - p.y * q.x + p.z * q.w},
                   -1);
}

at::Tensor quaternion_conjugate(const at::Tensor& q) { return q * at::tensor({1.0, -1.0, -1.0, -1.0}, q.options()); }

}  // namespace layers::zoo
