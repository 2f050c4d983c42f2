// Every garment type, for three seeds on two body shapes: one connected,
// manifold, consistently outward-wound mesh; edge lengths near the target;
// one UV chart per panel with UV areas matching 3D areas; the expected
// openings; and no vertex behind or within the clearance of the skin.
#include <gtest/gtest.h>

#include <set>

#include "garment_fixture.h"
#include "layers/core/error.h"
#include "layers/data/format.h"
#include "layers/garment/garment_recipes.h"

namespace layers::garment {
namespace {

using test::garment;
using test::inspect;

// Openings per type (neckline or face opening, hems, cuffs or armholes, waist).
int expected_openings(const std::string& type) {
  if (type == "skirt") return 2;
  if (type == "pants") return 3;
  if (type == "jumpsuit") return 5;
  return 4;
}

class GarmentType : public ::testing::TestWithParam<std::string> {};

TEST_P(GarmentType, BuildsSewnOutwardMeshes) {
  const std::string type = GetParam();
  const double h = 0.02;
  for (int shape = 0; shape < 2; ++shape)
    for (std::uint64_t seed = 1; seed <= 3; ++seed) {
      SCOPED_TRACE(type + " shape " + std::to_string(shape) + " seed " + std::to_string(seed));
      const GarmentMesh& g = garment(type, shape, seed, h);
      ASSERT_GT(g.num_vertices(), 500);
      EXPECT_EQ(g.type, type);
      EXPECT_EQ(g.layer, garment_layer(type));
      geometry::validate(g.mesh(), type);
      const test::MeshReport r = inspect(g, test::skin(shape), h);
      EXPECT_EQ(r.over_shared_edges, 0);
      EXPECT_EQ(r.misoriented_edges, 0);
      EXPECT_EQ(r.components, 1);
      EXPECT_EQ(r.boundary_loops, expected_openings(type));
      EXPECT_EQ(r.boundary_flag_mismatch, 0);
      EXPECT_GT(r.outward, type == "jacket_hood" ? 0.9 : 0.97);  // a hood hangs over the shoulders
      EXPECT_GT(r.edges_in_band, 0.95);
      EXPECT_NEAR(r.uv_area_ratio, 1.0, 0.08);
      EXPECT_EQ(r.uv_flipped, 0);
      EXPECT_EQ(r.uv_shared_across_panels, 0);
      for (std::size_t p = 0; p < r.uv_charts.size(); ++p) EXPECT_EQ(r.uv_charts[p], 1) << g.panel_names[p];
      ASSERT_EQ(g.panel.size(), g.num_faces());
      EXPECT_EQ(g.panel.minCoeff(), 0);
      EXPECT_EQ(g.panel.maxCoeff(), static_cast<int>(g.panel_names.size()) - 1);
      const ContactCount c = count_contact(g.vertices, test::skin(shape), GarmentParams().body_clearance - 1e-4);
      EXPECT_EQ(c.behind, 0);
      EXPECT_EQ(c.too_close, 0);
    }
}

INSTANTIATE_TEST_SUITE_P(AllTypes, GarmentType, ::testing::ValuesIn(garment_types()),
                         [](const ::testing::TestParamInfo<std::string>& info) { return info.param; });

// layers::data's garment-type table and the garment builder's recipes name
// the same types: adding a type is one entry in each.
TEST(GarmentType, EveryTypeHasARecipeAndEveryRecipeAType) {
  std::set<std::string> table, made;
  for (const data::GarmentTypeInfo& t : data::garment_type_table()) {
    if (t.layer != data::kAnyLayer) {
      EXPECT_TRUE(table.insert(t.name).second) << t.name;
    }
  }
  for (const Recipe& r : recipes()) EXPECT_TRUE(made.insert(r.type).second) << r.type;
  EXPECT_EQ(table, made);
  EXPECT_EQ(std::set<std::string>(garment_types().begin(), garment_types().end()), made);
  for (const data::GarmentTypeInfo& t : data::garment_type_table()) {
    if (t.layer == data::kAnyLayer) {  // a user's mesh: no template
      EXPECT_EQ(std::string(t.name), "imported");
      continue;
    }
    EXPECT_TRUE(t.layer == 0 || t.layer == 1) << t.name;
    EXPECT_EQ(garment_layer(t.name), t.layer) << t.name;
    // A subset is the paper's, of an inner garment under a jacket.
    if (std::string(t.subset) != "") {
      EXPECT_EQ(t.layer, 0) << t.name;
    }
  }
}

TEST(GarmentType, LayersAndNames) {
  EXPECT_EQ(garment_types().size(), 8u);
  EXPECT_EQ(garment_layer("jacket"), 1);
  EXPECT_EQ(garment_layer("jacket_hood"), 1);
  for (const char* inner : {"dress", "dress_belt", "jumpsuit", "tshirt", "pants", "skirt"})
    EXPECT_EQ(garment_layer(inner), 0);
  try {
    garment_layer("hat");
    FAIL() << "expected an InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    for (const auto& t : garment_types()) EXPECT_NE(what.find(t), std::string::npos) << what;
    EXPECT_NE(what.find("hat"), std::string::npos);
  }
  EXPECT_THROW(build_garment("hat", test::tpose(0), GarmentParams(), 1), InputError);
}

TEST(GarmentType, PanelsAreTheSewingPattern) {
  auto names = [](const GarmentMesh& g) { return std::set<std::string>(g.panel_names.begin(), g.panel_names.end()); };
  EXPECT_EQ(names(garment("skirt", 0, 1)), (std::set<std::string>{"skirt_front", "skirt_back"}));
  EXPECT_EQ(names(garment("pants", 0, 1)),
            (std::set<std::string>{"pants_left_front", "pants_left_back", "pants_right_front", "pants_right_back"}));
  const auto jacket = names(garment("jacket_hood", 0, 1));
  for (const char* p : {"front_left", "front_right", "back", "sleeve_left", "sleeve_right", "hood_left", "hood_right"})
    EXPECT_EQ(jacket.count(p), 1u) << p;
  const auto belted = names(garment("dress_belt", 0, 1));
  for (const char* p : {"front", "back", "belt_front", "belt_back", "skirt_front", "skirt_back"})
    EXPECT_EQ(belted.count(p), 1u) << p;
}

}  // namespace
}  // namespace layers::garment
