// MGNet UV splat and sample: a smooth field on a UV grid survives splat +
// sample, constants exactly; seam vertices are splatted into every chart
// and averaged back; charts are normalised by their bounding box; a chart
// without extent is a clear error.
#include <gtest/gtest.h>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/mgnet/uv_splat.h"
#include "mgnet_fixture.h"

namespace mg = layers::mgnet;
using layers::mgnet::testing::grid_garment;
using layers::mgnet::testing::grid_uv;

namespace {

// An n x n flat grid garment over [0,1]^2 (UV = xy), given UV offset/scale.
layers::zoo::GarmentStatic flat_grid(std::int64_t n) {
  const at::Tensor uv = grid_uv(n, n);
  return grid_garment("flat", 0, at::cat({uv, at::zeros({n * n, 1})}, 1), n, n);
}

// Two smooth fields of (u, v).
at::Tensor smooth_field(const at::Tensor& uv) {
  const at::Tensor u = uv.select(1, 0), v = uv.select(1, 1);
  return at::stack({at::sin(2 * u) + at::cos(2 * v), u * v + 0.5 * v}, 1);
}

}  // namespace

TEST(UvSplat, WeightsArePartitionsOfUnityInsideTheImage) {
  const mg::UvSplat s = mg::garment_splat(flat_grid(9), 16, "flat");
  EXPECT_EQ(s.images, 1);
  EXPECT_EQ(s.vertices, 81);
  ASSERT_EQ(s.vertex.size(0), 81);  // one UV point per vertex (no seams)
  EXPECT_TRUE(at::allclose(s.weight.sum(1), at::ones({81}), 1e-6, 1e-6));
  EXPECT_GE(s.weight.min().item<float>(), 0.0f);
  EXPECT_GE(s.pixel.min().item<std::int64_t>(), 0);
  EXPECT_LT(s.pixel.max().item<std::int64_t>(), 16 * 16);
  // Corner UVs land exactly on corner pixels.
  EXPECT_NEAR(s.weight_sum[0].item<float>(), 1.0f, 1e-6);
  EXPECT_NEAR(s.weight_sum[16 * 16 - 1].item<float>(), 1.0f, 1e-6);
  EXPECT_NEAR(s.weight_sum.sum().item<float>(), 81.0f, 1e-3);
}

TEST(UvSplat, SplatThenSampleReproducesASmoothField) {
  const std::int64_t n = 41, R = 16;
  const layers::zoo::GarmentStatic g = flat_grid(n);
  const mg::UvSplat s = mg::garment_splat(g, R, "flat");
  const at::Tensor field = smooth_field(g.uv);
  const at::Tensor image = mg::splat(s, field);
  ASSERT_EQ(image.sizes(), (at::IntArrayRef{1, 2, R, R}));
  const at::Tensor back = mg::sample(s, image);
  ASSERT_EQ(back.sizes(), field.sizes());
  const at::Tensor error = (back - field).abs().amax(1);
  const at::Tensor uv = g.uv;
  const at::Tensor interior = (uv > 0.1).all(1) & (uv < 0.9).all(1);
  // The field varies by ~2 over the square; a pixel is 1/15 wide. Inside,
  // the symmetric splat kernel leaves a second-order error (measured
  // 0.0073); border pixels only see vertices on one side, a first-order
  // bias (measured 0.058).
  EXPECT_LT(error.masked_select(interior).max().item<float>(), 0.01f);
  EXPECT_LT(error.max().item<float>(), 0.08f);
  // A constant field comes back exactly, borders included.
  const at::Tensor constant = at::full({n * n, 1}, 0.7f);
  EXPECT_TRUE(at::allclose(mg::sample(s, mg::splat(s, constant)), constant, 1e-5, 1e-6));
  // Pixels carry the weighted mean: nothing splatted is amplified.
  EXPECT_LE(image.abs().max().item<float>(), field.abs().max().item<float>() + 1e-5);
}

TEST(UvSplat, SampleInterpolatesBilinearlyAtEachUvPoint) {
  // An image equal to its column coordinate x / (R-1) samples back as u.
  const std::int64_t R = 8;
  const layers::zoo::GarmentStatic g = flat_grid(5);
  const mg::UvSplat s = mg::garment_splat(g, R, "flat");
  const at::Tensor columns = at::linspace(0, 1, R).repeat({R, 1}).reshape({1, 1, R, R});
  EXPECT_TRUE(at::allclose(mg::sample(s, columns).squeeze(1), g.uv.select(1, 0), 1e-5, 1e-6));
}

TEST(UvSplat, SeamVerticesLieInEveryChartAndAverageBack) {
  // Two triangles sharing edge 1-2, each in its own chart (UVs 0-2 and 3-5).
  layers::zoo::GarmentStatic g;
  g.name = "seam";
  g.faces = at::tensor({0, 1, 2, 2, 1, 3}, at::kLong).reshape({2, 3});
  g.rest = at::tensor({0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f, 1.f, 1.f, 0.f}).reshape({4, 3});
  g.uv = at::tensor({0.f, 0.f, 1.f, 0.f, 0.f, 1.f, 2.f, 1.f, 3.f, 0.f, 3.f, 1.f}).reshape({6, 2});
  g.uv_faces = at::tensor({0, 1, 2, 3, 4, 5}, at::kLong).reshape({2, 3});
  const mg::UvSplat s = mg::garment_splat(g, 8, "seam");
  EXPECT_EQ(s.vertex.size(0), 6);
  EXPECT_TRUE(at::equal(s.points_per_vertex, at::tensor({1.f, 2.f, 2.f, 1.f})));
  // u normalised by the bounding box [0, 3]: vertex 1 sits at u = 1/3 and
  // 1, vertex 2 at 0 and 2/3.
  const at::Tensor columns = at::linspace(0, 1, 8).repeat({8, 1}).reshape({1, 1, 8, 8});
  const at::Tensor u = mg::sample(s, columns).squeeze(1);
  EXPECT_TRUE(at::allclose(u, at::tensor({0.f, 2.f / 3.f, 1.f / 3.f, 1.f}), 1e-5, 1e-6)) << u;
}

TEST(UvSplat, ChartsAreNormalisedPerAxisAndGarmentsStack) {
  layers::zoo::GarmentStatic a = flat_grid(5), b = flat_grid(4);
  b.uv = grid_uv(4, 4, 2.0f, -1.0f, 3.0f, 0.5f);  // another chart: u in [2,5], v in [-1,-0.5]
  const mg::UvSplat sa = mg::garment_splat(a, 8, "a"), sb = mg::garment_splat(b, 8, "b");
  EXPECT_NEAR(sb.uv.min().item<float>(), 0.0f, 1e-6);
  EXPECT_NEAR(sb.uv.max().item<float>(), 1.0f, 1e-6);
  const mg::UvSplat both = mg::concatenate({sa, sb});
  EXPECT_EQ(both.images, 2);
  EXPECT_EQ(both.vertices, 25 + 16);
  const at::Tensor f = at::cat({at::full({25, 1}, 1.f), at::full({16, 1}, 2.f)});
  const at::Tensor image = mg::splat(both, f);
  ASSERT_EQ(image.sizes(), (at::IntArrayRef{2, 1, 8, 8}));
  EXPECT_FLOAT_EQ(image[0].max().item<float>(), 1.f);  // each garment only in its own image
  EXPECT_FLOAT_EQ(image[1].max().item<float>(), 2.f);
  EXPECT_TRUE(at::allclose(mg::sample(both, image), f, 1e-5, 1e-6));
  EXPECT_EQ(mg::coverage(both).sizes(), (at::IntArrayRef{2, 1, 8, 8}));
}

TEST(UvSplat, ChartWithoutExtentIsAnInputError) {
  layers::zoo::GarmentStatic g = flat_grid(4);
  g.uv.select(1, 1).fill_(0.25f);  // every v the same
  const std::string message =
      layers::test::error_of<layers::InputError>([&] { mg::garment_splat(g, 8, "sequence 's' garments[0] (flat)"); });
  EXPECT_NE(message.find("garments[0] (flat)"), std::string::npos) << message;
  EXPECT_NE(message.find("uv"), std::string::npos) << message;
  EXPECT_NE(message.find("non-zero range"), std::string::npos) << message;
}
