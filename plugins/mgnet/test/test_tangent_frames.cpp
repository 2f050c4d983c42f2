// MGNet tangent frames: UV-aligned on a flat grid, orthonormal and
// right-handed on a curved garment, rotating with the mesh, and exact
// round trips of displacements between world and frame coordinates.
#include <gtest/gtest.h>

#include <cmath>

#include "layers/mgnet/tangent_frames.h"
#include "mgnet_fixture.h"

namespace mg = layers::mgnet;
using namespace layers::mgnet::testing;

namespace {

mg::TangentBasis basis_of(const layers::zoo::GarmentStatic& g) {
  return mg::tangent_basis(g.faces, g.uv_faces, g.uv, g.rest.size(0));
}

// Rotation by `angle` about the unit axis (x, y, z).
at::Tensor rotation(double angle, double x, double y, double z) {
  const double c = std::cos(angle), s = std::sin(angle), k = 1 - c;
  return at::tensor({float(c + x * x * k), float(x * y * k - z * s), float(x * z * k + y * s), float(y * x * k + z * s),
                     float(c + y * y * k), float(y * z * k - x * s), float(z * x * k - y * s), float(z * y * k + x * s),
                     float(c + z * z * k)})
      .reshape({3, 3});
}

void expect_orthonormal(const at::Tensor& frames) {
  const at::Tensor gram = at::matmul(frames, frames.transpose(1, 2));
  EXPECT_TRUE(at::allclose(gram, at::eye(3).expand_as(gram), 1e-5, 1e-5));
  EXPECT_TRUE(at::allclose(at::linalg_det(frames), at::ones({frames.size(0)}), 1e-5, 1e-5));
}

}  // namespace

TEST(TangentFrames, FlatGridFramesFollowTheUvAxes) {
  const at::Tensor uv = grid_uv(5, 6);
  const layers::zoo::GarmentStatic g = grid_garment("flat", 0, at::cat({uv, at::zeros({30, 1})}, 1), 5, 6);
  const at::Tensor frames = mg::vertex_frames(basis_of(g), g.rest);
  ASSERT_EQ(frames.sizes(), (at::IntArrayRef{30, 3, 3}));
  EXPECT_TRUE(at::allclose(frames, at::eye(3).expand({30, 3, 3}), 1e-6, 1e-6));
  // Scaling the chart or the mesh along one axis keeps the frames.
  const at::Tensor stretched = g.rest * at::tensor({3.f, 0.5f, 1.f});
  EXPECT_TRUE(at::allclose(mg::vertex_frames(basis_of(g), stretched), frames, 1e-6, 1e-6));
}

TEST(TangentFrames, CurvedGarmentFramesAreOrthonormalAndTangentToTheSurface) {
  const Scene scene = two_garment_scene("frames");
  const layers::zoo::GarmentStatic& g = scene.statics.garments[0];
  const at::Tensor frames = mg::vertex_frames(basis_of(g), g.rest);
  expect_orthonormal(frames);
  // The cylinder is (r cos a, y, -r sin a) with a growing with u: the
  // normal is radial (outward) and the tangent dP/du is (-sin a, 0, -cos a).
  const at::Tensor radial = at::stack({g.rest.select(1, 0), at::zeros({g.rest.size(0)}), g.rest.select(1, 2)}, 1);
  const at::Tensor outward = radial / radial.norm(2, 1, true);
  const at::Tensor n = frames.select(1, 2), t = frames.select(1, 0);
  EXPECT_GT((n * outward).sum(1).min().item<float>(), 0.95f);
  EXPECT_LT(t.select(1, 1).abs().max().item<float>(), 0.05f);
  const at::Tensor angle = at::atan2(-g.rest.select(1, 2), g.rest.select(1, 0));
  const at::Tensor expected_t = at::stack({-at::sin(angle), at::zeros_like(angle), -at::cos(angle)}, 1);
  EXPECT_GT((t * expected_t).sum(1).min().item<float>(), 0.95f);
}

TEST(TangentFrames, FramesRotateWithTheMesh) {
  const Scene scene = two_garment_scene("frames");
  const layers::zoo::GarmentStatic& g = scene.statics.garments[1];
  const mg::TangentBasis basis = basis_of(g);
  const at::Tensor moved = scene.garment(1, 3);  // deformed by the wave
  const at::Tensor rot = rotation(0.7, 0.6, 0.0, 0.8);
  const at::Tensor frames = mg::vertex_frames(basis, moved);
  const at::Tensor rotated = mg::vertex_frames(basis, at::matmul(moved, rot.t()) + at::tensor({0.3f, -1.f, 2.f}));
  // Each frame row (t, b, n) is rotated: F' = F R^T.
  EXPECT_TRUE(at::allclose(rotated, at::matmul(frames, rot.t()), 1e-4, 1e-5));
  // So a displacement rotated with the mesh has the same local components.
  at::manual_seed(3);
  const at::Tensor d = at::randn({g.rest.size(0), 3});
  EXPECT_TRUE(at::allclose(mg::to_frame(rotated, at::matmul(d, rot.t())), mg::to_frame(frames, d), 1e-4, 1e-5));
}

TEST(TangentFrames, DisplacementRoundTrip) {
  const Scene scene = two_garment_scene("frames");
  const layers::zoo::GarmentStatic& g = scene.statics.garments[0];
  const at::Tensor frames = mg::vertex_frames(basis_of(g), scene.garment(0, 5));
  at::manual_seed(1);
  const at::Tensor d = at::randn({g.rest.size(0), 3});
  const at::Tensor local = mg::to_frame(frames, d);
  EXPECT_TRUE(at::allclose(mg::from_frame(frames, local), d, 1e-5, 1e-5));
  EXPECT_TRUE(at::allclose(mg::to_frame(frames, mg::from_frame(frames, d)), d, 1e-5, 1e-5));
  // Lengths are kept and (0, 0, 1) is the normal.
  EXPECT_TRUE(at::allclose(local.norm(2, 1), d.norm(2, 1), 1e-5, 1e-5));
  const at::Tensor up = at::tensor({0.f, 0.f, 1.f}).expand({g.rest.size(0), 3});
  EXPECT_TRUE(at::allclose(mg::from_frame(frames, up), frames.select(1, 2), 1e-6, 1e-6));
}

TEST(TangentFrames, DegenerateUvsAndIsolatedVerticesStillGiveFrames) {
  // Face 0 has collapsed UVs (no tangent), face 1 UVs = xy; vertex 4 is in
  // no face.
  const at::Tensor faces = at::tensor({0, 1, 2, 1, 3, 2}, at::kLong).reshape({2, 3});
  const at::Tensor uv = at::tensor({0.f, 0.f, 0.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 1.f}).reshape({6, 2});
  const at::Tensor uv_faces = at::tensor({0, 1, 2, 3, 4, 5}, at::kLong).reshape({2, 3});
  const at::Tensor positions =
      at::tensor({0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f, 5.f, 5.f, 5.f}).reshape({5, 3});
  const at::Tensor frames = mg::vertex_frames(mg::tangent_basis(faces, uv_faces, uv, 5), positions);
  expect_orthonormal(frames);
  EXPECT_TRUE(at::allclose(frames[4][2], at::tensor({0.f, 1.f, 0.f})));  // isolated: +y
  // Vertex 0 (only in the collapsed face) falls back to the x axis, which
  // here is also the UV tangent of the others.
  EXPECT_TRUE(at::allclose(frames.narrow(0, 0, 4), at::eye(3).expand({4, 3, 3}), 1e-6, 1e-6));
}
