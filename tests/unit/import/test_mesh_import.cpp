// Users' garment meshes (libs/import) on files written inside the tests:
// an OBJ with a UV seam (its vertex order kept, UVs per corner), a GLB from
// our own writer (data/glb.h) whose seam splits vertices (welded back), a file in centimetres with its
// scale, and each refusal of the cloth-mesh checks and of the side file.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/data/glb.h"
#include "layers/import/garment_file.h"
#include "layers/import/mesh_checks.h"
#include "layers/import/mesh_import.h"
#include "temp_dir.h"

namespace layers::import {
namespace {

// A tube of `cols` x 2 quads (radius 0.2 m, 0.5 m tall), open at both ends,
// as OBJ text: the UVs are cut at the seam, so the seam's two columns of
// positions get two UVs each ("v" lines are shared, "vt" lines are not).
std::string tube_obj(int cols, double scale = 1.0) {
  std::string s = "# tube\n";
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < cols; ++c) {
      const double a = 2 * M_PI * c / cols;
      s += "v " + std::to_string(0.2 * std::sin(a) * scale) + " " + std::to_string(0.25 * r * scale) + " " +
           std::to_string(0.2 * std::cos(a) * scale) + "\n";
    }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c <= cols; ++c)
      s += "vt " + std::to_string(double(c) / cols) + " " + std::to_string(r / 2.0) + "\n";
  auto v = [&](int r, int c) { return r * cols + (c % cols) + 1; };
  auto t = [&](int r, int c) { return r * (cols + 1) + c + 1; };
  for (int r = 0; r < 2; ++r)
    for (int c = 0; c < cols; ++c) {
      auto corner = [&](int rr, int cc) { return std::to_string(v(rr, cc)) + "/" + std::to_string(t(rr, cc)); };
      s += "f " + corner(r, c) + " " + corner(r, c + 1) + " " + corner(r + 1, c + 1) + "\n";
      s += "f " + corner(r, c) + " " + corner(r + 1, c + 1) + " " + corner(r + 1, c) + "\n";
    }
  return s;
}

std::string message_of(const std::function<void()>& f) { return test::error_of<InputError>(f); }

TEST(MeshImport, ObjKeepsItsVertexOrderAndItsUvsPerCorner) {
  test::TempDir dir("import");
  const std::string path = dir.write("tube.obj", tube_obj(8));
  const ImportedMesh m = import_mesh(path);
  ASSERT_EQ(m.mesh.vertices.rows(), 24);  // 3 rings of 8
  for (int c = 0; c < 8; ++c)             // in the file's order
    EXPECT_NEAR(m.mesh.vertices(8 + c, 0), 0.2 * std::sin(2 * M_PI * c / 8), 1e-6);
  EXPECT_EQ(m.mesh.faces.rows(), 32);
  EXPECT_EQ(m.file_vertices, 24);  // our OBJ reader keeps the v lines
  ASSERT_EQ(m.uv_faces.size(), 32u * 3);
  // Every corner's UV is the one the OBJ gave it: u follows the angle, with
  // the seam's corners at u = 1 on the faces that close the tube.
  for (Eigen::Index f = 0; f < m.mesh.faces.rows(); ++f) {
    float umin = 2, umax = -1;
    for (int c = 0; c < 3; ++c) {
      const float u = m.uv[2 * m.uv_faces[3 * f + c]], v = m.uv[2 * m.uv_faces[3 * f + c] + 1];
      const Eigen::RowVector3f p = m.mesh.vertices.row(m.mesh.faces(f, c));
      EXPECT_NEAR(v, p.y() / 0.5f, 1e-5);
      umin = std::min(umin, u), umax = std::max(umax, u);
    }
    EXPECT_LE(umax - umin, 1.0f / 8 + 1e-5) << "face " << f << " spans the seam in UV";
  }
  EXPECT_NO_THROW(check_cloth_mesh(m.mesh, path));  // open at both ends: allowed
}

TEST(MeshImport, GlbSplitAtASeamIsWeldedBack) {
  // Two triangles sharing an edge, stored with their own copies of its two
  // vertices (as a UV seam splits them): 6 file vertices, 4 welded.
  test::TempDir dir("import");
  data::GlbMesh mesh{
      "cloth", {0, 1, 2, 3, 4, 5}, {{0, 0, 0, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.25f}}};
  const std::string path = dir.file("cloth.glb");
  std::ofstream(path, std::ios::binary) << data::glb_bytes({mesh}, 30);
  const ImportedMesh m = import_mesh(path);
  EXPECT_EQ(m.file_vertices, 6);
  ASSERT_EQ(m.mesh.vertices.rows(), 4);
  std::vector<std::vector<float>> got, want = {{0, 0, 0}, {0.5f, 0, 0}, {0.5f, 0.5f, 0}, {0, 0.5f, 0.25f}};
  for (Eigen::Index i = 0; i < 4; ++i)
    got.push_back({m.mesh.vertices(i, 0), m.mesh.vertices(i, 1), m.mesh.vertices(i, 2)});
  std::sort(got.begin(), got.end());
  std::sort(want.begin(), want.end());
  EXPECT_EQ(got, want);
  // The shared edge is one edge again: the second face uses the first's corners.
  ASSERT_EQ(m.mesh.faces.rows(), 2);
  EXPECT_EQ(m.mesh.faces(1, 0), m.mesh.faces(0, 0));
  EXPECT_EQ(m.mesh.faces(1, 1), m.mesh.faces(0, 2));
  EXPECT_TRUE(m.uv.empty());
}

// A glTF of two triangles with its own buffer file; `third` is the second
// triangle's last vertex index (4 vertices).
std::string two_triangle_gltf(const test::TempDir& dir, std::uint32_t third) {
  const float pos[12] = {0, 0, 0, 0.5f, 0, 0, 0.5f, 0.5f, 0, 0, 0.5f, 0.1f};
  const std::uint32_t idx[6] = {0, 1, 2, 0, 2, third};
  std::ofstream bin(dir.file("two.bin"), std::ios::binary);
  bin.write(reinterpret_cast<const char*>(pos), sizeof pos);
  bin.write(reinterpret_cast<const char*>(idx), sizeof idx);
  bin.close();
  const std::string json =
      R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
      R"("meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1}]}],)"
      R"("buffers":[{"byteLength":72,"uri":"two.bin"}],)"
      R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":24}],)"
      R"("accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[0.5,0.5,0.1]},)"
      R"({"bufferView":1,"componentType":5125,"count":6,"type":"SCALAR"}]})";
  std::ofstream(dir.file("two.gltf")) << json;
  return dir.file("two.gltf");
}

// Issue 62 S2: assimp drops faces whose indices are out of range and only
// warns; a garment that lost faces so is refused, not simulated.
TEST(MeshImport, AFaceIndexOutOfRangeIsRefusedNotDropped) {
  test::TempDir dir("import");
  EXPECT_EQ(import_mesh(two_triangle_gltf(dir, 3)).mesh.faces.rows(), 2);
  const std::string said = message_of([&] { import_mesh(two_triangle_gltf(dir, 1000000)); });
  EXPECT_NE(said.find("two.gltf: faces: expected vertex indices within each mesh's vertices, got faces with indices "
                      "out of range"),
            std::string::npos)
      << said;
}

// Issue 62 M6: a .gltf buffer that is a FIFO hung assimp forever.
TEST(MeshImport, AGltfBufferThatIsAPipeIsRefusedBeforeAssimpOpensIt) {
  test::TempDir dir("import");
  const std::string gltf = two_triangle_gltf(dir, 3);
  std::filesystem::remove(dir.file("two.bin"));
  ASSERT_EQ(mkfifo(dir.file("two.bin").c_str(), 0600), 0);
  const std::string said = message_of([&] { import_mesh(gltf); });
  EXPECT_NE(said.find("two.gltf: uri: expected buffers and images that are regular files, got 'two.bin', a pipe"),
            std::string::npos)
      << said;
}

// Two triangles (a 1 m square) as PLY: `vertices` and `faces` are what the
// header declares (the data holds 4 and 2), binary little-endian or text.
std::string square_ply(const test::TempDir& dir, std::uint64_t vertices, std::uint64_t faces, bool binary) {
  std::string s = std::string("ply\nformat ") + (binary ? "binary_little_endian" : "ascii") + " 1.0\nelement vertex " +
                  std::to_string(vertices) + "\nproperty float x\nproperty float y\nproperty float z\nelement face " +
                  std::to_string(faces) + "\nproperty list uchar int vertex_indices\nend_header\n";
  const float xyz[4][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const std::int32_t tri[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& v : xyz) {
    if (binary)
      s.append(reinterpret_cast<const char*>(v), sizeof v);
    else
      s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  }
  for (const auto& f : tri) {
    if (binary) {
      s += static_cast<char>(3);
      s.append(reinterpret_cast<const char*>(f), sizeof f);
    } else {
      s += "3 " + std::to_string(f[0]) + " " + std::to_string(f[1]) + " " + std::to_string(f[2]) + "\n";
    }
  }
  const std::string path =
      dir.file(std::string(binary ? "bin" : "text") + std::to_string(vertices) + "_" + std::to_string(faces) + ".ply");
  std::ofstream(path, std::ios::binary) << s;
  return path;
}

// The same square as binary STL declaring `facets`.
std::string square_stl(const test::TempDir& dir, std::uint32_t facets) {
  std::string s(80, ' ');
  s.append(reinterpret_cast<const char*>(&facets), 4);
  const float tri[2][4][3] = {{{0, 0, 1}, {0, 0, 0}, {1, 0, 0}, {1, 1, 0}},
                              {{0, 0, 1}, {0, 0, 0}, {1, 1, 0}, {0, 1, 0}}};
  for (const auto& t : tri) {
    s.append(reinterpret_cast<const char*>(t), sizeof t);
    s.append(2, '\0');
  }
  const std::string path = dir.file("square" + std::to_string(facets) + ".stl");
  std::ofstream(path, std::ios::binary) << s;
  return path;
}

// Issue 62 M1 and messages 5 and 9: counts a header declares beyond what
// the file holds are refused before assimp allocates for them (a 227-byte
// PLY declaring 2e9 vertices took 23.5 GB); files that hold what they
// declare still reach assimp.
TEST(MeshImport, DeclaredCountsBeyondTheFileAreRefusedBeforeAssimp) {
  test::TempDir dir("import");
  for (bool binary : {true, false}) {
    const std::string said = message_of([&] { import_mesh(square_ply(dir, 4, 2, binary)); });
    EXPECT_EQ(said.find("element"), std::string::npos) << "a file holding what it declares: " << said;
  }
  EXPECT_EQ(message_of([&] { import_mesh(square_stl(dir, 2)); }).find("facet count"), std::string::npos);
  std::string said = message_of([&] { import_mesh(square_ply(dir, 2000000000, 2, true)); });
  EXPECT_NE(said.find("bin2000000000_2.ply: element vertex: expected at most "), std::string::npos) << said;
  EXPECT_NE(said.find("got a header declaring 2000000000"), std::string::npos) << said;
  said = message_of([&] { import_mesh(square_ply(dir, 4, 10000000, false)); });
  EXPECT_NE(said.find("text4_10000000.ply: element face: expected at most "), std::string::npos) << said;
  said = message_of([&] { import_mesh(square_stl(dir, 2147483648u)); });
  EXPECT_NE(said.find("square2147483648.stl: facet count: expected at most 2 facets (50 bytes each after the 84-byte "
                      "header of a 184-byte binary STL), got 2147483648"),
            std::string::npos)
      << said;
}

// Issue 62 message 4: a GLB whose JSON chunk does not parse was "No
// suitable reader found"; now the chunk and the parser's line.
TEST(MeshImport, AGlbWithBrokenJsonSaysSo) {
  test::TempDir dir("import");
  const std::vector<float> xyz = {0, 0, 0, 1, 0, 0, 1, 1, 0};
  std::string glb = data::glb_bytes({data::GlbMesh{"tri", {0, 1, 2}, {xyz, xyz}}}, 30.0);
  glb[20] = 'x';  // the JSON chunk's opening brace
  const std::string path = dir.file("broken.glb");
  std::ofstream(path, std::ios::binary) << glb;
  const std::string said = message_of([&] { import_mesh(path); });
  EXPECT_NE(said.find("broken.glb: GLB JSON chunk: expected valid JSON, got [json.exception.parse_error"),
            std::string::npos)
      << said;
  glb[0] = 'X';
  std::ofstream(path, std::ios::binary | std::ios::trunc) << glb;
  EXPECT_NE(message_of([&] { import_mesh(path); }).find("GLB header: expected the magic 'glTF'"), std::string::npos);
}

TEST(MeshImport, CentimetresAreRefusedUntilScaled) {
  test::TempDir dir("import");
  const std::string path = dir.write("tube_cm.obj", tube_obj(8, 100.0));
  const ImportedMesh cm = import_mesh(path);
  const std::string e = message_of([&] { check_cloth_mesh(cm.mesh, path); });
  EXPECT_NE(e.find("scale"), std::string::npos) << e;
  EXPECT_NE(e.find("largest extent of 50 m"), std::string::npos) << e;
  const ImportedMesh m = import_mesh(path, 0.01);
  EXPECT_NO_THROW(check_cloth_mesh(m.mesh, path));
  EXPECT_NEAR(m.mesh.vertices.col(1).maxCoeff(), 0.5f, 1e-6);
}

TEST(MeshImport, DegenerateAndNonManifoldFacesAreOneLineEach) {
  test::TempDir dir("import");
  geometry::TriMesh m;
  m.vertices.resize(5, 3);
  m.vertices << 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0, 0, 0, 0.5f, 0.25f, 0, 0;  // vertex 4 on edge 0-1
  m.faces.resize(2, 3);
  m.faces << 0, 1, 2, 0, 4, 1;  // the second has no area
  std::string e = message_of([&] { check_cloth_mesh(m, "g.obj"); });
  EXPECT_NE(e.find("1 degenerate, the first face 1"), std::string::npos) << e;
  m.faces.resize(3, 3);
  m.faces << 0, 1, 2, 0, 1, 3, 1, 0, 4;
  m.vertices.row(4) << 0.2f, -0.3f, 0.1f;
  e = message_of([&] { check_cloth_mesh(m, "g.obj"); });
  EXPECT_NE(e.find("1 edges in three or more faces, the first between vertices 0 and 1"), std::string::npos) << e;
  m.vertices(2, 1) = NAN;
  EXPECT_NE(message_of([&] { check_cloth_mesh(m, "g.obj"); }).find("finite"), std::string::npos);
}

TEST(MeshImport, FacesWoundInwardsOrBothWaysAreRefused) {
  test::TempDir dir("import");
  const ImportedMesh tube = import_mesh(dir.write("tube.obj", tube_obj(8)));
  geometry::TriMesh inwards = tube.mesh;
  for (Eigen::Index f = 0; f < inwards.faces.rows(); ++f) std::swap(inwards.faces(f, 1), inwards.faces(f, 2));
  EXPECT_NE(message_of([&] { check_cloth_mesh(inwards, "t.obj"); }).find("normals pointing inwards"),
            std::string::npos);
  geometry::TriMesh mixed = tube.mesh;
  std::swap(mixed.faces(3, 1), mixed.faces(3, 2));  // one face the other way
  EXPECT_NE(message_of([&] { check_cloth_mesh(mixed, "t.obj"); }).find("edges whose two faces disagree"),
            std::string::npos);
}

TEST(MeshImport, ANonFiniteVertexIsRefusedBeforeWelding) {
  test::TempDir dir("import");
  const std::string path = dir.write("nan.obj", "v nan 0 0\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 3 4\nf 2 3 4\n");
  EXPECT_NE(message_of([&] { import_mesh(path); }).find("a non-finite value in vertex 0"), std::string::npos);
}

TEST(MeshImport, MissingOrUnreadableFilesAreOneLine) {
  test::TempDir dir("import");
  EXPECT_NE(message_of([&] { import_mesh(dir.file("none.obj")); }).find("no such file"), std::string::npos);
  const std::string junk = dir.write("junk.fbx", "not a mesh at all");
  EXPECT_NE(message_of([&] { import_mesh(junk); }).find("a mesh file assimp reads"), std::string::npos);
}

// Issue 62 M2 and messages 1-2: a side file is parsed with the config's
// bounds (values counted before the tree is built: a 20 MB side file took
// 4.78 GB), and a NUL byte or deep nesting is one line naming the file.
TEST(GarmentFile, SideFilesAreBoundedLikeConfigs) {
  test::TempDir dir("import");
  const std::string mesh = dir.write("dress.obj", tube_obj(8));
  std::string many = "attributes:\n  mass: 0.3\nnotes:\n";
  for (int i = 0; i < 1000001; ++i) many += "- x\n";
  dir.write("dress.yaml", many);
  std::string said = message_of([&] { read_garment_file("file:" + mesh); });
  EXPECT_NE(said.find("dress.yaml:"), std::string::npos) << said;
  EXPECT_NE(said.find("expected YAML of at most 1000000 values"), std::string::npos) << said;
  dir.write("dress.yaml", "a: " + std::string(100000, '['));
  said = message_of([&] { read_garment_file("file:" + mesh); });
  EXPECT_NE(said.find("dress.yaml:1: expected values nested at most 64 levels deep"), std::string::npos) << said;
  dir.write("dress.yaml", std::string("name: \"a\0i\"\n", 13));
  said = message_of([&] { read_garment_file("file:" + mesh); });
  EXPECT_NE(said.find("dress.yaml:1: expected YAML text, got a NUL byte (a binary file?) at byte 8"), std::string::npos)
      << "[" << said << "]";
}

TEST(GarmentFile, SideFileGivesNameScaleAndAttributes) {
  test::TempDir dir("import");
  const std::string mesh = dir.write("dress.obj", tube_obj(8));
  GarmentFile g = read_garment_file("file:" + mesh);
  EXPECT_EQ(g.name, "dress");
  EXPECT_EQ(g.scale, 1.0);
  EXPECT_TRUE(g.side_file.empty());
  dir.write("dress.yaml", "name: my dress\nscale: 0.01\nattributes: {mass: 0.3, bending: 40}\n");
  g = read_garment_file("file:" + mesh);
  EXPECT_EQ(g.name, "my dress");
  EXPECT_EQ(g.scale, 0.01);
  EXPECT_EQ(g.attributes, (std::map<std::string, double>{{"mass", 0.3}, {"bending", 40}}));
  dir.write("dress.yaml", "colour: red\n");
  EXPECT_NE(
      message_of([&] { read_garment_file("file:" + mesh); }).find("name, scale, self_contact, remesh or attributes"),
      std::string::npos);
  dir.write("dress.yaml", "scale: 0\n");
  EXPECT_NE(message_of([&] { read_garment_file("file:" + mesh); }).find("a positive factor"), std::string::npos);
  dir.write("dress.yaml", "attributes: {mass: -1}\n");
  EXPECT_NE(message_of([&] { read_garment_file("file:" + mesh); }).find("attributes.mass"), std::string::npos);
  EXPECT_NE(message_of([&] { read_garment_file("file:" + dir.file("no.obj")); }).find("no such file"),
            std::string::npos);
}

}  // namespace
}  // namespace layers::import
