// The shared training losses (layers/zoo/losses.h) on hand-made cases:
// values computable by hand, gradient directions, zero and finite gradients
// when nothing collides, agreement with layers::geometry, errors.
#include <gtest/gtest.h>

#include <cmath>

#include "error_of.h"
#include "grid_mesh.h"
#include "layers/core/error.h"
#include "layers/geometry/normals.h"
#include "layers/zoo/losses.h"

namespace zoo = layers::zoo;
namespace g = layers::geometry;
using layers::test::error_of;

namespace {

at::Tensor points(std::initializer_list<float> xyz) { return at::tensor(std::vector<float>(xyz)).reshape({-1, 3}); }

at::Tensor to_tensor(const g::Points& p) {
  return at::from_blob(const_cast<float*>(p.data()), {p.rows(), 3}, at::kFloat).clone();
}
at::Tensor to_tensor(const g::Faces& f) {
  return at::from_blob(const_cast<int*>(f.data()), {f.rows(), 3}, at::kInt).clone();
}

// The unit square at z = 0 as a 5 x 5 grid (normals +z), as tensors.
struct Plane {
  at::Tensor vertices, faces;
};
Plane plane() {
  g::TriMesh m = layers::test::unit_square_grid(5, 0.0f);
  return {to_tensor(m.vertices), to_tensor(m.faces)};
}

// A UV sphere of radius r around c, outward normals (rings x segments).
Plane sphere(float r, int rings, int segments) {
  std::vector<float> v;
  std::vector<int> f;
  v.insert(v.end(), {0.f, r, 0.f});  // north pole
  for (int i = 1; i < rings; ++i) {
    const double theta = M_PI * i / rings;
    for (int j = 0; j < segments; ++j) {
      const double phi = 2 * M_PI * j / segments;
      v.push_back(float(r * std::sin(theta) * std::cos(phi)));
      v.push_back(float(r * std::cos(theta)));
      v.push_back(float(-r * std::sin(theta) * std::sin(phi)));
    }
  }
  v.insert(v.end(), {0.f, -r, 0.f});  // south pole
  const int south = 1 + (rings - 1) * segments;
  auto ring = [&](int i, int j) { return 1 + (i - 1) * segments + (j % segments); };
  for (int j = 0; j < segments; ++j) {
    f.insert(f.end(), {0, ring(1, j), ring(1, j + 1)});
    for (int i = 1; i + 1 < rings; ++i) {
      f.insert(f.end(), {ring(i, j), ring(i + 1, j), ring(i + 1, j + 1)});
      f.insert(f.end(), {ring(i, j), ring(i + 1, j + 1), ring(i, j + 1)});
    }
    f.insert(f.end(), {ring(rings - 1, j), south, ring(rings - 1, j + 1)});
  }
  return {at::tensor(v).reshape({-1, 3}), at::tensor(f, at::kInt).reshape({-1, 3})};
}

float z_of(const at::Tensor& t, std::int64_t row) { return t[row][2].item<float>(); }

}  // namespace

TEST(Losses, PositionMseIsTheMeanSquaredDistance) {
  at::Tensor truth = points({0, 0, 0, 1, 0, 0, 0, 1, 0});
  at::Tensor pred = truth + points({0.003f, 0, 0, 0, 0.004f, 0, 0, 0, 0});
  // (0.003^2 + 0.004^2 + 0) / 3
  EXPECT_NEAR(zoo::position_mse(pred, truth).item<double>(), (9e-6 + 16e-6) / 3, 1e-10);
  EXPECT_EQ(zoo::position_mse(truth, truth).item<double>(), 0.0);
}

TEST(Losses, NormalLossIsZeroForIdenticalMeshesAndFourPerFlippedFace) {
  // Two separate triangles in the z = 0 plane, normals +z.
  at::Tensor truth = points({0, 0, 0, 1, 0, 0, 0, 1, 0, 2, 0, 0, 3, 0, 0, 2, 1, 0});
  at::Tensor faces = at::tensor({0, 1, 2, 3, 4, 5}, at::kInt).reshape({2, 3});
  EXPECT_EQ(zoo::normal_loss(truth, truth, faces).item<double>(), 0.0);
  // Translated and scaled: same normals.
  EXPECT_NEAR(zoo::normal_loss(truth * 2.5 + 1.0, truth, faces).item<double>(), 0.0, 1e-12);

  // Mirror the first triangle's third corner: its normal becomes -z,
  // |n - (-n)|^2 = 4 on one face of two.
  at::Tensor flipped = truth.clone();
  flipped[2][1] = -1.0f;
  EXPECT_NEAR(zoo::normal_loss(flipped, truth, faces).item<double>(), 2.0, 1e-6);
}

// The paper's vertex-normal loss on a folded quad: a corner lifted by 1
// tilts the second face to (-1, -1, 1)/sqrt(3); the shared vertices' area-
// weighted normals turn halfway, to (-1, -1, 2)/sqrt(6), the lifted one
// all the way and the far one not at all, so the vertex and the face losses
// differ.
TEST(Losses, VertexNormalLossAveragesTheFacesAroundEachVertex) {
  at::Tensor truth = points({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0});
  at::Tensor pred = points({0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 1});
  at::Tensor faces = at::tensor({0, 1, 2, 1, 3, 2}, at::kLong).reshape({2, 3});
  EXPECT_EQ(zoo::vertex_normal_loss(truth, truth, faces).item<double>(), 0.0);
  EXPECT_NEAR(zoo::vertex_normal_loss(pred * 2.5 + 1.0, pred, faces).item<double>(), 0.0, 1e-6);
  const double shared = 2 - 4 / std::sqrt(6.0), lifted = 2 - 2 / std::sqrt(3.0);
  EXPECT_NEAR(zoo::vertex_normal_loss(pred, truth, faces).item<double>(), (2 * shared + lifted) / 4, 1e-6);
  EXPECT_NEAR(zoo::normal_loss(pred, truth, faces).item<double>(), lifted / 2, 1e-6);
  at::Tensor x = pred.clone().requires_grad_(true);
  zoo::vertex_normal_loss(x, truth, faces).backward();
  EXPECT_GT(x.grad().abs().sum().item<double>(), 0.0);
  EXPECT_TRUE(x.grad().isfinite().all().item<bool>());
}

TEST(Losses, NormalLossOfADegenerateFaceIsFiniteWithAFiniteGradient) {
  at::Tensor truth = points({0, 0, 0, 1, 0, 0, 0, 1, 0});
  at::Tensor pred = points({0, 0, 0, 1, 0, 0, 2, 0, 0}).requires_grad_(true);  // collinear
  at::Tensor faces = at::tensor({0, 1, 2}, at::kLong).reshape({1, 3});
  at::Tensor loss = zoo::normal_loss(pred, truth, faces);
  EXPECT_NEAR(loss.item<double>(), 1.0, 1e-6);  // normal 0 against a unit normal
  loss.backward();
  // No direction to prefer: a zero gradient, not a huge one.
  EXPECT_EQ(pred.grad().abs().max().item<float>(), 0.0f);
}

TEST(Losses, VertexOneCentimetreBehindAPlane) {
  Plane body = plane();
  const double eps = 0.005;
  // Above grid vertex (0.5, 0.5): 1 cm behind the plane.
  at::Tensor garment = points({0.5f, 0.5f, -0.01f}).requires_grad_(true);
  at::Tensor loss = zoo::body_collision_loss(garment, body.vertices, body.faces, eps);
  EXPECT_NEAR(loss.item<double>(), 0.015 * 0.015, 1e-9);  // (eps - d)^2, d = -0.01
  loss.backward();
  // d(loss)/dz = -2 (eps - d) = -0.03: descending pushes the vertex out (+z).
  EXPECT_NEAR(garment.grad()[0][2].item<float>(), -0.03f, 1e-6f);
  EXPECT_NEAR(garment.grad()[0][0].item<float>(), 0.0f, 1e-7f);
  EXPECT_NEAR(garment.grad()[0][1].item<float>(), 0.0f, 1e-7f);
}

TEST(Losses, BodyCollisionAveragesOverViolatingVerticesOnly) {
  Plane body = plane();
  const double eps = 0.005;
  at::Tensor garment = points({0.25f, 0.25f, -0.01f,  // d = -0.01: (0.015)^2
                               0.75f, 0.5f, 0.002f,   // d = 0.002 < eps: (0.003)^2
                               0.5f, 0.75f, 0.1f})    // outside: no term
                           .requires_grad_(true);
  at::Tensor loss = zoo::body_collision_loss(garment, body.vertices, body.faces, eps);
  EXPECT_NEAR(loss.item<double>(), (0.015 * 0.015 + 0.003 * 0.003) / 2, 1e-9);
  loss.backward();
  EXPECT_LT(z_of(garment.grad(), 0), 0.0f);
  EXPECT_LT(z_of(garment.grad(), 1), 0.0f);
  EXPECT_EQ(z_of(garment.grad(), 2), 0.0f);
}

TEST(Losses, NoViolationGivesZeroAndAZeroFiniteGradient) {
  Plane body = plane();
  at::Tensor garment = points({0.5f, 0.5f, 0.02f, 0.1f, 0.9f, 0.3f}).requires_grad_(true);
  at::Tensor loss = zoo::body_collision_loss(garment, body.vertices, body.faces, 0.005);
  EXPECT_EQ(loss.item<double>(), 0.0);
  loss.backward();
  ASSERT_TRUE(garment.grad().defined());
  EXPECT_TRUE(at::isfinite(garment.grad()).all().item<bool>());
  EXPECT_EQ(garment.grad().abs().max().item<float>(), 0.0f);
}

TEST(Losses, GradientPushesPenetratingVerticesOutOfASphere) {
  Plane body = sphere(0.3f, 12, 24);
  // Sanity of the fixture: outward normals.
  at::Tensor n = zoo::vertex_normals(body.vertices, body.faces);
  ASSERT_GT((n * body.vertices).sum(1).min().item<float>(), 0.0f);

  // Vertices 1 cm inside the surface in several directions.
  at::Tensor dirs = points({1, 0, 0, 0, 1, 0, -0.6f, 0.3f, 0.74f, 0.2f, -0.9f, -0.4f});
  dirs = dirs / dirs.norm(2, {1}, true);
  at::Tensor garment = (dirs * 0.29f).requires_grad_(true);
  at::Tensor loss = zoo::body_collision_loss(garment, body.vertices, body.faces, 0.005);
  EXPECT_GT(loss.item<double>(), 0.0);
  loss.backward();
  // Descending (-grad) points outward for every vertex.
  at::Tensor outward = -(garment.grad() * dirs).sum(1);
  EXPECT_GT(outward.min().item<float>(), 0.0f) << garment.grad();

  // A few gradient steps reduce the loss and move the vertices out.
  at::Tensor x = garment.detach().clone();
  double before = loss.item<double>();
  for (int i = 0; i < 20; ++i) {
    x.requires_grad_(true);
    at::Tensor l = zoo::body_collision_loss(x, body.vertices, body.faces, 0.005);
    l.backward();
    x = (x - 0.1 * x.grad()).detach();
  }
  double after = zoo::body_collision_loss(x, body.vertices, body.faces, 0.005).item<double>();
  EXPECT_LT(after, before);
  EXPECT_GT(x.norm(2, {1}).min().item<float>(), 0.29f);
}

TEST(Losses, LayerCollisionReachesBothLayers) {
  Plane inner = plane();
  at::Tensor inner_v = inner.vertices.clone().requires_grad_(true);
  // Above grid vertex 12 = (0.5, 0.5, 0): 1 cm behind the inner layer.
  at::Tensor outer = points({0.5f, 0.5f, -0.01f, 0.0f, 1.0f, 0.2f}).requires_grad_(true);
  at::Tensor loss = zoo::layer_collision_loss(outer, inner_v, inner.faces, 0.005);
  EXPECT_NEAR(loss.item<double>(), 0.015 * 0.015, 1e-9);
  loss.backward();
  EXPECT_NEAR(z_of(outer.grad(), 0), -0.03f, 1e-6f);  // outer pushed out (+z)
  EXPECT_EQ(z_of(outer.grad(), 1), 0.0f);
  EXPECT_NEAR(z_of(inner_v.grad(), 12), 0.03f, 1e-6f);  // inner pushed in (-z)
  // Only the nearest inner vertex moves (the normal's gradient is along
  // the normal itself here, which the unit normalisation removes).
  at::Tensor others = at::cat({inner_v.grad().slice(0, 0, 12), inner_v.grad().slice(0, 13)});
  EXPECT_LT(others.abs().max().item<float>(), 1e-6f);
}

TEST(Losses, ConstantAndDifferentiableSurfacesGiveTheSameLoss) {
  // A body that needs no gradient takes its normals from layers::geometry,
  // one that does from torch: the same numbers either way.
  Plane body = sphere(0.3f, 10, 16);
  at::Tensor garment =
      at::cat({points({0.29f, 0.01f, 0.0f, 0.0f, -0.295f, 0.02f}), points({0.1f, 0.2f, -0.15f, -0.2f, 0.1f, 0.18f})});
  at::Tensor constant = zoo::body_collision_loss(garment, body.vertices, body.faces, 0.01);
  at::Tensor moving = zoo::body_collision_loss(garment, body.vertices.clone().requires_grad_(true), body.faces, 0.01);
  EXPECT_GT(constant.item<double>(), 0.0);
  EXPECT_NEAR(constant.item<double>(), moving.item<double>(), 1e-9);
  EXPECT_FALSE(constant.requires_grad());
  EXPECT_TRUE(moving.requires_grad());
}

TEST(Losses, VertexNormalsMatchGeometry) {
  g::TriMesh m = layers::test::unit_square_grid(6, 0.0f);
  for (int i = 0; i < m.num_vertices(); ++i) {
    const float x = m.vertices(i, 0), y = m.vertices(i, 1);
    m.vertices(i, 2) = 0.3f * std::sin(3 * x) * std::cos(2 * y);  // a bent sheet
  }
  g::Points expected = g::vertex_normals(m.vertices, m.faces);
  at::Tensor got = zoo::vertex_normals(to_tensor(m.vertices), to_tensor(m.faces));
  EXPECT_LT((got - to_tensor(expected)).abs().max().item<float>(), 1e-5f);
  EXPECT_NEAR(got.norm(2, {1}).min().item<float>(), 1.0f, 1e-5f);

  // A vertex of no face gets 0.
  at::Tensor v = at::cat({to_tensor(m.vertices), points({5, 5, 5})});
  at::Tensor n = zoo::vertex_normals(v, to_tensor(m.faces));
  EXPECT_EQ(n[m.num_vertices()].abs().sum().item<float>(), 0.0f);
}

TEST(Losses, DoublePrecisionInputsStayDouble) {
  Plane body = plane();
  at::Tensor garment = at::tensor({0.5, 0.5, -0.01}, at::kDouble).reshape({1, 3});
  at::Tensor loss = zoo::body_collision_loss(garment, body.vertices.to(at::kDouble), body.faces, 0.005);
  EXPECT_EQ(loss.scalar_type(), at::kDouble);
  EXPECT_NEAR(loss.item<double>(), 0.015 * 0.015, 1e-12);
}

TEST(Losses, NonFiniteGarmentGivesANonFiniteLoss) {
  Plane body = plane();
  at::Tensor garment = points({0.5f, 0.5f, NAN, 0.2f, 0.2f, -0.01f});
  EXPECT_FALSE(std::isfinite(zoo::body_collision_loss(garment, body.vertices, body.faces, 0.005).item<double>()));
}

TEST(Losses, EmptyInputsGiveZero) {
  Plane body = plane();
  EXPECT_EQ(zoo::body_collision_loss(at::zeros({0, 3}), body.vertices, body.faces, 0.005).item<double>(), 0.0);
  EXPECT_EQ(zoo::layer_collision_loss(points({0, 0, -1}), at::zeros({0, 3}), at::zeros({0, 3}, at::kInt), 0.005)
                .item<double>(),
            0.0);
}

TEST(Losses, BadInputsAreClearErrors) {
  Plane body = plane();
  at::Tensor x = points({0.5f, 0.5f, 0.1f});
  EXPECT_NE(error_of<layers::Error>([&] {
              zoo::position_mse(x, at::zeros({2, 3}));
            }).find("position_mse: truth"),
            std::string::npos);
  EXPECT_NE(error_of<layers::Error>([&] {
              zoo::position_mse(at::zeros({3, 2}), at::zeros({3, 2}));
            }).find("expected a floating-point tensor [*, 3]"),
            std::string::npos);
  EXPECT_NE(error_of<layers::Error>([&] {
              zoo::normal_loss(x, x, at::tensor({0, 0, 1}, at::kInt).reshape({1, 3}));
            }).find("normal_loss: faces: expected indices in [0, 1), got values in [0, 1]"),
            std::string::npos);
  EXPECT_NE(error_of<layers::Error>([&] {
              zoo::body_collision_loss(x, body.vertices, body.faces.to(at::kFloat), 0.005);
            }).find("body_collision_loss: body_faces: expected an integer tensor"),
            std::string::npos);
  at::Tensor bad_body = body.vertices.clone();
  bad_body[3][1] = INFINITY;
  EXPECT_NE(error_of<layers::Error>([&] {
              zoo::body_collision_loss(x, bad_body, body.faces, 0.005);
            }).find("body_collision_loss: body: expected finite positions"),
            std::string::npos);
  EXPECT_NE(error_of<layers::Error>([&] {
              zoo::layer_collision_loss(x, body.vertices, body.faces, NAN);
            }).find("layer_collision_loss: eps: expected a finite distance"),
            std::string::npos);
  EXPECT_NE(error_of<layers::Error>([&] {
              zoo::vertex_normals(at::Tensor(), body.faces);
            }).find("vertex_normals: vertices: expected a floating-point tensor [*, 3], got nothing"),
            std::string::npos);
}

TEST(Losses, RunOnTheInputsDevice) {
  if (!at::hasCUDA()) GTEST_SKIP() << "no CUDA device in this build";
  Plane body = plane();
  at::Tensor garment = points({0.5f, 0.5f, -0.01f, 0.25f, 0.75f, 0.002f});
  at::Tensor on_gpu = garment.to(at::kCUDA).requires_grad_(true);
  at::Tensor inner = body.vertices.to(at::kCUDA).requires_grad_(true);
  at::Tensor body_loss = zoo::body_collision_loss(on_gpu, body.vertices.to(at::kCUDA), body.faces, 0.005);
  at::Tensor layer_loss = zoo::layer_collision_loss(on_gpu, inner, body.faces.to(at::kCUDA), 0.005);
  EXPECT_TRUE(body_loss.is_cuda());
  EXPECT_NEAR(body_loss.item<double>(),
              zoo::body_collision_loss(garment, body.vertices, body.faces, 0.005).item<double>(), 1e-9);
  (body_loss + layer_loss).backward();
  EXPECT_TRUE(on_gpu.grad().is_cuda());
  EXPECT_TRUE(inner.grad().is_cuda());
  EXPECT_LT(on_gpu.grad()[0][2].item<float>(), 0.0f);
  EXPECT_TRUE(zoo::normal_loss(on_gpu, on_gpu.detach(), at::tensor({0, 1, 0}, at::kInt).reshape({1, 3})).is_cuda());
}
