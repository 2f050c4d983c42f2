// Generation settings and randomness: config reading and range checks,
// determinism for a seed, sizes that vary with the seed, and vertex
// counts that follow the target edge length.
#include <gtest/gtest.h>

#include "garment_fixture.h"
#include "layers/core/error.h"

namespace layers::garment {
namespace {

using test::garment;

TEST(GarmentParams, ReadsFromConfigAndChecksRanges) {
  const GarmentParams p = cfg::read<GarmentParams>(
      cfg::parse("edge_length: 0.03\nflare: [0.1, 0.2]\nlayer_clearance: [0.02, 0.025]\n", "garments.yaml"),
      "garments");
  EXPECT_DOUBLE_EQ(p.edge_length, 0.03);
  EXPECT_EQ(p.flare, (std::vector<double>{0.1, 0.2}));
  EXPECT_NO_THROW(validate(p));
  const GarmentParams back = cfg::read<GarmentParams>(cfg::to_node(p), "garments");
  EXPECT_EQ(back.layer_clearance, p.layer_clearance);
  EXPECT_THROW(cfg::read<GarmentParams>(cfg::parse("edge_lenght: 0.03\n", "garments.yaml"), "garments"), InputError);
  EXPECT_THROW(cfg::read<GarmentParams>(cfg::parse("edge_length: 0\n", "garments.yaml"), "garments"), InputError);
  GarmentParams bad;
  bad.skirt_length = {0.6, 0.2};
  try {
    validate(bad);
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "skirt_length");
  }
  bad = GarmentParams();
  bad.edge_length = 0.5;
  EXPECT_THROW(validate(bad), InputError);
  bad = GarmentParams();
  bad.ease_loose = {0.02};
  EXPECT_THROW(build_garment("tshirt", test::tpose(0), bad, 1), InputError);
}

TEST(GarmentParams, SameSeedSameGarment) {
  const GarmentMesh a = build_garment("jacket_hood", test::tpose(0), GarmentParams(), 42);
  const GarmentMesh b = build_garment("jacket_hood", test::tpose(0), GarmentParams(), 42);
  ASSERT_EQ(a.num_vertices(), b.num_vertices());
  EXPECT_TRUE(a.vertices == b.vertices);
  EXPECT_TRUE(a.faces == b.faces);
  EXPECT_TRUE(a.uv == b.uv);
  EXPECT_TRUE(a.uv_faces == b.uv_faces);
  EXPECT_TRUE(a.panel == b.panel);
  EXPECT_EQ(a.style, b.style);
}

TEST(GarmentParams, SeedsChangeSizes) {
  for (const auto& type : garment_types()) {
    const GarmentMesh& a = garment(type, 0, 1);
    const GarmentMesh& b = garment(type, 0, 2);
    EXPECT_NE(a.style, b.style) << type;
    EXPECT_NE(a.num_vertices(), b.num_vertices()) << type;
    for (const char* key : {"ease", "length"}) {
      if (std::isnan(a.style_value(key))) continue;
      EXPECT_NE(a.style_value(key), b.style_value(key)) << type << " " << key;
    }
  }
  // Lengths land where the ranges say: a skirt's hem between crotch and ankle.
  const auto marks = garment::measure(test::tpose(0));
  for (std::uint64_t seed = 1; seed <= 3; ++seed) {
    const GarmentMesh& s = garment("skirt", 0, seed);
    const double hem = s.vertices.col(1).minCoeff();
    EXPECT_LT(hem, marks.crotch);
    EXPECT_GT(hem, marks.ankle);
  }
}

TEST(GarmentParams, HalvingTheEdgeLengthQuadruplesVertices) {
  for (const char* type : {"tshirt", "pants"}) {
    const int coarse = garment(type, 0, 7, 0.04).num_vertices();
    const int fine = garment(type, 0, 7, 0.02).num_vertices();
    const double ratio = static_cast<double>(fine) / coarse;
    EXPECT_GT(ratio, 3.4) << type;
    EXPECT_LT(ratio, 4.6) << type;
  }
}

}  // namespace
}  // namespace layers::garment
