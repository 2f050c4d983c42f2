// Quaternion helpers shared by the model plugins (see rotations.h).
#include "layers/zoo/rotations.h"

namespace layers::zoo {
namespace {

at::Tensor normalized(const at::Tensor& q) { return q / q.norm(2, {-1}, /*keepdim=*/true).clamp_min(1e-12); }

}  // namespace

at::Tensor rotation_matrices(const at::Tensor& quaternions) {
  const at::Tensor q = normalized(quaternions);
  const at::Tensor w = q.select(1, 0), x = q.select(1, 1), y = q.select(1, 2), z = q.select(1, 3);
  const at::Tensor rows = at::stack({1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y),
                                     2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x),
                                     2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)},
                                    1);
  return rows.view({-1, 3, 3});
}

at::Tensor rotate_z(const at::Tensor& quaternions) {
  const at::Tensor q = normalized(quaternions);
  const at::Tensor w = q.select(-1, 0), x = q.select(-1, 1), y = q.select(-1, 2), z = q.select(-1, 3);
  return at::stack({2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)}, -1);
}

at::Tensor heading_quaternions(const at::Tensor& quaternions) {
  const at::Tensor forward = rotate_z(quaternions);
  const at::Tensor half = 0.5 * at::atan2(forward.select(1, 0), forward.select(1, 2));  // atan2(0, 0) = 0
  const at::Tensor zero = at::zeros_like(half);
  return at::stack({at::cos(half), zero, at::sin(half), zero}, 1);
}

at::Tensor quaternion_multiply(const at::Tensor& a, const at::Tensor& b) {
  const at::Tensor aw = a.select(1, 0), ax = a.select(1, 1), ay = a.select(1, 2), az = a.select(1, 3);
  const at::Tensor bw = b.select(1, 0), bx = b.select(1, 1), by = b.select(1, 2), bz = b.select(1, 3);
  return at::stack({aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
                    aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw},
                   1);
}

at::Tensor quaternion_conjugate(const at::Tensor& q) {
  return q * at::tensor({1.0, -1.0, -1.0, -1.0}, q.options());
}

}  // namespace layers::zoo
