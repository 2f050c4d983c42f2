// The quaternion helpers shared by the model plugins: matrices, +z images,
// headings (yaw about +y), products and conjugates against each other.
#include <gtest/gtest.h>

#include <cmath>

#include "layers/zoo/rotations.h"

namespace zoo = layers::zoo;

namespace {

// Unit quaternion of `angle` about `axis` (x, y, z), as [1,4].
at::Tensor about(double angle, double x, double y, double z) {
  const double s = std::sin(angle / 2), n = std::sqrt(x * x + y * y + z * z);
  return at::tensor({std::cos(angle / 2), s * x / n, s * y / n, s * z / n}, at::kDouble).unsqueeze(0);
}

}  // namespace

TEST(Rotations, MatricesProductsAndConjugatesAgree) {
  const at::Tensor a = about(0.7, 1, 2, -0.5), b = about(-1.9, 0.2, -1, 0.4);
  const at::Tensor ra = zoo::rotation_matrices(a)[0], rb = zoo::rotation_matrices(b)[0];
  EXPECT_TRUE(at::allclose(at::matmul(ra, ra.t()), at::eye(3, at::kDouble), 1e-12, 1e-12));
  EXPECT_TRUE(
      at::allclose(zoo::rotation_matrices(zoo::quaternion_multiply(a, b))[0], at::matmul(ra, rb), 1e-12, 1e-12));
  EXPECT_TRUE(at::allclose(zoo::rotation_matrices(zoo::quaternion_conjugate(a))[0], ra.t(), 1e-12, 1e-12));
  EXPECT_TRUE(at::allclose(zoo::rotate_z(a)[0], ra.select(1, 2), 1e-12, 1e-12));
  // Leading dimensions broadcast: one quaternion times a batch of two.
  const at::Tensor ab = at::cat({a, b});
  EXPECT_TRUE(
      at::allclose(zoo::quaternion_multiply(a[0], ab), zoo::quaternion_multiply(a.expand({2, 4}), ab), 1e-15, 1e-15));
  EXPECT_EQ(zoo::rotation_matrices(ab.unsqueeze(0)).sizes(), (at::IntArrayRef{1, 2, 3, 3}));
  // Any length: normalised first.
  EXPECT_TRUE(at::allclose(zoo::rotation_matrices(3 * a)[0], ra, 1e-12, 1e-12));
  // 90 degrees about +y takes +z to +x.
  EXPECT_TRUE(
      at::allclose(zoo::rotate_z(about(M_PI / 2, 0, 1, 0))[0], at::tensor({1.0, 0.0, 0.0}, at::kDouble), 1e-12, 1e-12));
}

TEST(Rotations, HeadingKeepsTheYawAndDropsTheTilt) {
  for (double yaw : {0.0, 0.4, -2.5, 3.0}) {
    const at::Tensor y = about(yaw, 0, 1, 0);
    EXPECT_TRUE(at::allclose(zoo::heading_quaternions(y), y, 1e-9, 1e-9)) << yaw;
    // A forward lean (about the body's own x axis) and a sideways roll
    // (about its own z axis) leave the heading where it was.
    const at::Tensor leaned =
        zoo::quaternion_multiply(zoo::quaternion_multiply(y, about(0.5, 1, 0, 0)), about(-0.3, 0, 0, 1));
    EXPECT_TRUE(at::allclose(zoo::heading_quaternions(leaned), y, 1e-9, 1e-9)) << yaw;
  }
  // Batched, and +z pointing straight up has heading 0 (the identity).
  const at::Tensor up = about(-M_PI / 2, 1, 0, 0);
  EXPECT_TRUE(at::allclose(zoo::rotate_z(up)[0], at::tensor({0.0, 1.0, 0.0}, at::kDouble), 1e-12, 1e-12));
  const at::Tensor h = zoo::heading_quaternions(at::cat({about(1.0, 0, 1, 0), up}));
  ASSERT_EQ(h.sizes(), (at::IntArrayRef{2, 4}));
  EXPECT_NEAR(h[1][0].item<double>(), 1.0, 1e-9);
  EXPECT_NEAR(h[0][2].item<double>(), std::sin(0.5), 1e-9);
}
