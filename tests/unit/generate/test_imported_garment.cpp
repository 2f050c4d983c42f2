// Users' own garments in the generator (generate/imported_garment.h): the
// templates of one scene written in their T-pose (`layers tpose`'s
// tpose_meshes) as OBJ and read back as garment files give the same rest
// shapes and simulate like the native scene; a garment shifted into the body and an outer garment inside the
// inner one are refused before any simulation, naming the count; the
// cylindrical UVs are in metres.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/obj.h"
#include "layers/generate/generator.h"
#include "layers/generate/imported_garment.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"
#include "layers/generate/tpose.h"
#include "temp_dir.h"
#include "test_paths.h"
#include "tiny_scene.h"

namespace layers::generate {
namespace {

TEST(ImportedGarment, TemplatesWrittenAndReadBackSimulateAsTheNativeScene) {
  test::TempDir dir("imported");
  const GeneratorConfig native = cfg::read<GeneratorConfig>(tiny_tree());
  const TPoseMeshes t = tpose_meshes(native, 0);
  ASSERT_TRUE(t.problem.empty()) << t.problem;
  ASSERT_EQ(t.garments.size(), 2u);
  for (const auto& [name, mesh] : t.garments) data::write_obj(dir.file(name + ".obj"), mesh);
  // The native jacket has no self-contact (the dress has, as an imported
  // garment has by default).
  dir.write("jacket.yaml", "self_contact: false\n");
  cfg::Node own_tree = tiny_tree();
  set_outfits(own_tree,
              "[{inner: ['file:" + dir.file("dress.obj") + "'], outer: 'file:" + dir.file("jacket.obj") + "'}]");
  const GeneratorConfig own = cfg::read<GeneratorConfig>(own_tree);
  check(own, "test");

  const data::SequenceData a = generate_one(native, dir.file("native"));
  const data::SequenceData b = generate_one(own, dir.file("own"));
  ASSERT_EQ(b.garments.size(), 2u);
  EXPECT_EQ(b.body.positions, a.body.positions);
  for (std::size_t g = 0; g < 2; ++g) {
    const data::GarmentData &x = a.garments[g], &y = b.garments[g];
    EXPECT_EQ(y.type, "imported");
    EXPECT_EQ(y.name, x.name);
    EXPECT_EQ(y.layer, x.layer);
    std::map<std::string, double> drawn = y.attributes;
    EXPECT_EQ(drawn.at("self_contact"), x.name == "dress" ? 1.0 : 0.0);  // the side file's, stored
    drawn.erase("self_contact");
    EXPECT_EQ(drawn, x.attributes);  // the same draw
    ASSERT_EQ(y.rest.size(), x.rest.size()) << "the file's vertices welded back to the template's";
    EXPECT_EQ(y.faces.size(), x.faces.size());
    // OBJ keeps the vertex order: the same vertices, within the float
    // round trip of moving them to the T-pose and back.
    double rest = 0;
    for (std::size_t i = 0; i < x.rest.size(); ++i) rest = std::max<double>(rest, std::abs(y.rest[i] - x.rest[i]));
    EXPECT_EQ(y.faces, x.faces);
    EXPECT_LT(rest, 1e-5) << x.name << " rest shape";
    // The simulated frames: the last bits of the round trip through the
    // T-pose grow through the contact passes, so they are compared as the
    // generator regression compares runs (tolerances.yaml: the garments'
    // mean speed within 0.02 mm + 3%), and vertex by vertex on average.
    const double vx = garment_speed_mm(x, a.n_frames), vy = garment_speed_mm(y, b.n_frames);
    EXPECT_LE(std::abs(vy - vx), 0.02 + 0.03 * vx) << x.name << " speed " << vy << " against " << vx << " mm/frame";
    const double frames = mean_distance_mm(x.positions, y.positions);
    EXPECT_LT(frames, 0.5) << x.name << " positions";
    std::printf("%s: rest within %.2g m, frames %.3g mm apart on average, speed %.3f / %.3f mm per frame\n",
                x.name.c_str(), rest, frames, vx, vy);
  }
}

TEST(ImportedGarment, InsideTheBodyOrInsideTheInnerLayerIsRefusedBeforeSimulating) {
  test::TempDir dir("imported");
  const GeneratorConfig native = cfg::read<GeneratorConfig>(tiny_tree());
  const TPoseMeshes t = tpose_meshes(native, 0);
  std::map<std::string, data::ObjMesh> meshes(t.garments.begin(), t.garments.end());
  data::ObjMesh sunk = meshes.at("dress");
  for (std::size_t i = 2; i < sunk.positions.size(); i += 3) sunk.positions[i] -= 0.08f;  // 8 cm back
  data::write_obj(dir.file("sunk.obj"), sunk);
  data::write_obj(dir.file("dress.obj"), meshes.at("dress"));
  data::write_obj(dir.file("jacket.obj"), meshes.at("jacket"));
  auto problem = [&](const std::string& inner, const std::string& outer) {
    cfg::Node tree = tiny_tree();
    set_outfits(tree, "[{inner: ['file:" + dir.file(inner) + "'], outer: 'file:" + dir.file(outer) + "'}]");
    const GeneratorConfig config = cfg::read<GeneratorConfig>(tree);
    const SceneSimulation scene(config, sample_scene(config, 0));
    return scene.problem();
  };
  std::string p = problem("sunk.obj", "jacket.obj");
  EXPECT_NE(p.find(dir.file("sunk.obj")), std::string::npos) << p;
  EXPECT_NE(p.find("vertices inside the body, most near the "), std::string::npos) << p;
  // The jacket as the inner garment: the dress over it is inside it.
  p = problem("jacket.obj", "dress.obj");
  EXPECT_NE(p.find("an outer garment that encloses the inner ones"), std::string::npos) << p;
  EXPECT_NE(p.find("vertices near them inside an inner garment"), std::string::npos) << p;
  EXPECT_EQ(problem("dress.obj", "jacket.obj"), "");
}

TEST(ImportedGarment, OutfitsOfTemplatesAndFilesAreNotMixed) {
  test::TempDir dir("imported");
  data::write_obj(dir.file("g.obj"), {0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0}, {0, 1, 2});
  cfg::Node tree = tiny_tree();
  set_outfits(tree, "[{inner: ['file:" + dir.file("g.obj") + "'], outer: jacket}]");
  try {
    check(cfg::read<GeneratorConfig>(tree), "c.yaml");
    FAIL() << "a mixed outfit was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("an outfit of templates only or of garment files only"), std::string::npos)
        << e.what();
  }
  set_outfits(tree, "[{inner: ['file:" + dir.file("none.obj") + "'], outer: none}]");
  try {
    check(cfg::read<GeneratorConfig>(tree), "c.yaml");
    FAIL() << "a missing garment file was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("no such file"), std::string::npos) << e.what();
  }
}

TEST(ImportedGarment, CylindricalUvsAreMetresAroundTheAxis) {
  // A ring of radius 0.3 m: u runs round it in metres, the back face's
  // corners unwrapped across the seam.
  geometry::TriMesh ring;
  const int n = 12;
  ring.vertices.resize(2 * n, 3);
  for (int k = 0; k < n; ++k)
    for (int r = 0; r < 2; ++r)
      ring.vertices.row(r * n + k) << 0.3f * std::sin(2 * M_PI * k / n), 0.2f * r, 0.3f * std::cos(2 * M_PI * k / n);
  ring.faces.resize(2 * n, 3);
  for (int k = 0; k < n; ++k) {
    const int k1 = (k + 1) % n;
    ring.faces.row(2 * k) << k, k1, n + k1;
    ring.faces.row(2 * k + 1) << k, n + k1, n + k;
  }
  std::vector<float> uv;
  std::vector<std::int32_t> uv_faces;
  cylindrical_uv(ring, Eigen::Vector3d::Zero(), uv, uv_faces);
  ASSERT_EQ(uv.size(), 2u * 3 * 2 * n);
  for (int f = 0; f < 2 * n; ++f) {
    float umin = 1e9f, umax = -1e9f;
    for (int c = 0; c < 3; ++c) {
      umin = std::min(umin, uv[2 * (3 * f + c)]);
      umax = std::max(umax, uv[2 * (3 * f + c)]);
      EXPECT_NEAR(uv[2 * (3 * f + c) + 1], ring.vertices(ring.faces(f, c), 1), 1e-6);
    }
    EXPECT_NEAR(umax - umin, 2 * M_PI * 0.3 / n, 1e-4) << "face " << f;  // one column's arc, seam included
  }
}

}  // namespace
}  // namespace layers::generate
