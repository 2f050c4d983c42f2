// OBJ and PC2 import/export: round trips, every face form, malformed
// inputs with line numbers or header fields, and sequence export.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstring>

#include <filesystem>
#include <fstream>

#include "error_of.h"
#include "file_bytes.h"
#include "gltf_validator.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/export.h"
#include "layers/data/obj.h"
#include "layers/data/pc2.h"
#include "synthetic_sequence.h"

namespace layers::data {
namespace {

using testing::TempDir;

TEST(DataObj, RoundTripWithUvIsBitIdentical) {
  TempDir dir;
  const auto seq = testing::make_sequence("o", 3);
  const GarmentData& g = seq.garments[0];
  const std::vector<float> positions(g.positions.begin(), g.positions.begin() + g.rest.size());
  write_obj(dir.file("g.obj"), positions, g.faces, g.uv, g.uv_faces);
  const ObjMesh back = read_obj(dir.file("g.obj"));
  EXPECT_EQ(back.positions, positions);
  EXPECT_EQ(back.faces, g.faces);
  EXPECT_EQ(back.uv, g.uv);
  EXPECT_EQ(back.uv_faces, g.uv_faces);

  write_obj(dir.file("b.obj"), ObjMesh{{0, 0, 0, 1, 0, 0, 0, 1, 0}, {0, 1, 2}, {}, {}});
  const ObjMesh plain = read_obj(dir.file("b.obj"));
  EXPECT_EQ(plain.faces, (std::vector<std::int32_t>{0, 1, 2}));
  EXPECT_TRUE(plain.uv_faces.empty());
}

TEST(DataObj, ReadsEveryFaceFormPolygonsAndNegativeIndices) {
  TempDir dir;
  testing::write_text(dir.file("m.obj"),
                      "# comment\r\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0 1.0\n"
                      "vn 0 0 1\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\ns off\n"
                      "f 1/1 2/2 3/3\n"              // v/vt
                      "f 1/1/1 3/3/1 4/4/1\n"        // v/vt/vn
                      "f -4/-4 -3/-3 -2/-2 -1/-1\n"  // quad, negative indices
                      "l 1 2\n");
  const ObjMesh m = read_obj(dir.file("m.obj"));
  EXPECT_EQ(m.n_vertices(), 4);
  EXPECT_EQ(m.faces, (std::vector<std::int32_t>{0, 1, 2, 0, 2, 3, 0, 1, 2, 0, 2, 3}));
  EXPECT_EQ(m.uv_faces, m.faces);

  testing::write_text(dir.file("n.obj"), "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\nf 1//1 2//1 3//1\nf 1 3 4 5\n");
  const ObjMesh n = read_obj(dir.file("n.obj"));
  EXPECT_EQ(n.faces, (std::vector<std::int32_t>{0, 1, 2, 0, 2, 3, 0, 3, 4}));
  EXPECT_TRUE(n.uv_faces.empty());
}

TEST(DataObj, MalformedInputsNameTheLine) {
  TempDir dir;
  const auto error_for = [&](const std::string& text) {
    testing::write_text(dir.file("bad.obj"), text);
    return test::error_of<InputError>([&] { read_obj(dir.file("bad.obj")); });
  };
  std::string e = error_for("v 0 0 0\nv 1 x 0\n");
  EXPECT_NE(e.find("bad.obj:2"), std::string::npos) << e;
  EXPECT_NE(e.find("expected a number after 'v', got 'x'"), std::string::npos) << e;
  e = error_for("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 4\n");
  EXPECT_NE(e.find("bad.obj:4"), std::string::npos) << e;
  EXPECT_NE(e.find("vertex index 4 out of range (the file has 3 vertices)"), std::string::npos) << e;
  e = error_for("v 0 0 0\nv 1 0 0\nf 1 2\n");
  EXPECT_NE(e.find("bad.obj:3: expected a face of at least 3 vertices, got 2"), std::string::npos) << e;
  e = error_for("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 0 1 2\n");
  EXPECT_NE(e.find("got 0"), std::string::npos) << e;
  e = error_for("v 0 0 0\nv 1 0 0\nv 0 1 0\nf -5 1 2\n");
  EXPECT_NE(e.find("before the first element"), std::string::npos) << e;
  e = error_for("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2 3\n");
  EXPECT_NE(e.find("bad.obj:5"), std::string::npos) << e;
  e = error_for("v 0 0\n");
  EXPECT_NE(e.find("expected 3 numbers after 'v', got 2"), std::string::npos) << e;
  // Issue 62 C1/S1: indices past int's range crashed (2^31 + 1) or wrapped
  // onto another vertex (2^32 + 2 read as 2).
  for (const char* index : {"2147483649", "4294967298", "2147483648/1"}) {
    e = error_for(std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1 2 ") + index + "\n");
    EXPECT_NE(e.find("bad.obj:5: expected an index of at most 2147483646"), std::string::npos) << e;
  }
  e = error_for("v 0 0 0\nv 1 0 0\nv 0 1 0\nvt 0 0\nf 1/1 2/1 3/4294967298\n");
  EXPECT_NE(e.find("got 4294967298"), std::string::npos) << e;
  EXPECT_NE(test::error_of<InputError>([&] { read_obj(dir.file("missing.obj")); }).find("missing.obj"),
            std::string::npos);
  EXPECT_NE(test::error_of<InputError>([&] {
              write_obj(dir.file("w.obj"), {0, 0, 0}, {0, 0, 1});
            }).find("faces"),
            std::string::npos);
}

TEST(DataPc2, RoundTripAndLayout) {
  TempDir dir;
  Pc2Cache cache;
  cache.header = Pc2Header{5, 10.0f, 1.0f, 3};
  for (int i = 0; i < 5 * 3 * 3; ++i) cache.positions.push_back(0.25f * float(i) - 3.0f);
  write_pc2(dir.file("c.pc2"), cache);
  EXPECT_EQ(std::filesystem::file_size(dir.file("c.pc2")), 32u + 12u * 5u * 3u);
  const std::string bytes = testing::read_text(dir.file("c.pc2"));
  EXPECT_EQ(bytes.substr(0, 12), std::string("POINTCACHE2\0", 12));
  EXPECT_EQ(bytes[12], 1);  // version, little-endian
  const Pc2Cache back = read_pc2(dir.file("c.pc2"));
  EXPECT_EQ(back.header.n_points, 5);
  EXPECT_EQ(back.header.n_samples, 3);
  EXPECT_EQ(back.header.start_frame, 10.0f);
  EXPECT_EQ(back.positions, cache.positions);
}

TEST(DataPc2, MalformedFilesAreRejected) {
  TempDir dir;
  Pc2Cache cache;
  cache.header = Pc2Header{2, 0.0f, 1.0f, 2};
  cache.positions.assign(12, 1.0f);
  write_pc2(dir.file("good.pc2"), cache);
  const std::string good = testing::read_text(dir.file("good.pc2"));

  std::string bad = good;
  bad[0] = 'X';
  testing::write_text(dir.file("sig.pc2"), bad);
  EXPECT_NE(
      test::error_of<InputError>([&] { read_pc2(dir.file("sig.pc2")); }).find("signature: expected \"POINTCACHE2\\0\""),
      std::string::npos);
  bad = good;
  bad[12] = 2;
  testing::write_text(dir.file("ver.pc2"), bad);
  EXPECT_NE(test::error_of<InputError>([&] { read_pc2(dir.file("ver.pc2")); }).find("file version: expected 1, got 2"),
            std::string::npos);
  testing::write_text(dir.file("short.pc2"), good.substr(0, good.size() - 4));
  const std::string e = test::error_of<InputError>([&] { read_pc2(dir.file("short.pc2")); });
  EXPECT_NE(e.find("file size: expected 80 bytes (32 + 12 x 2 points x 2 samples), got 76 bytes"), std::string::npos)
      << e;
  testing::write_text(dir.file("tiny.pc2"), good.substr(0, 20));
  EXPECT_NE(test::error_of<InputError>([&] { read_pc2(dir.file("tiny.pc2")); }).find("at least 32 bytes"),
            std::string::npos);
  cache.positions.pop_back();
  EXPECT_NE(test::error_of<InputError>([&] { write_pc2(dir.file("w.pc2"), cache); }).find("12 floats"),
            std::string::npos);
}

class DataExport : public ::testing::Test {
 protected:
  void SetUp() override {
    seq = testing::make_sequence("s", 4);
    DatasetWriter writer(dir.file("ds"));
    writer.add(seq);
    writer.set_split("train", {"s"});
    writer.finish();
  }
  TempDir dir;
  SequenceData seq;
};

TEST_F(DataExport, ObjFilePerFramePerMesh) {
  const Dataset ds = Dataset::open(dir.file("ds"));
  const auto files = export_sequence(ds, "s", ExportFormat::Obj, 2, 4, dir.file("out"));
  EXPECT_EQ(files.size(), 3u * 2u);
  const ObjMesh jacket = read_obj(dir.file("out/s_jacket_0003.obj"));
  EXPECT_EQ(jacket.positions, testing::frames_of(seq.garments[1].positions, seq.n_frames, 3, 1));
  EXPECT_EQ(jacket.uv, seq.garments[1].uv);
  const ObjMesh body = read_obj(dir.file("out/s_body_0002.obj"));
  EXPECT_EQ(body.positions, testing::frames_of(seq.body.positions, seq.n_frames, 2, 1));
  EXPECT_EQ(body.faces, seq.body.faces);
}

TEST_F(DataExport, Pc2CachePlusObjAtFirstFrame) {
  const Dataset ds = Dataset::open(dir.file("ds"));
  export_sequence(ds, "s", parse_export_format("pc2"), 1, -1, dir.file("out"));
  const Pc2Cache cache = read_pc2(dir.file("out/s_tshirt.pc2"));
  EXPECT_EQ(cache.header.start_frame, 1.0f);
  EXPECT_EQ(cache.header.n_samples, seq.n_frames - 1);
  EXPECT_EQ(cache.positions, testing::frames_of(seq.garments[0].positions, seq.n_frames, 1, seq.n_frames - 1));
  const ObjMesh mesh = read_obj(dir.file("out/s_tshirt.obj"));
  EXPECT_EQ(mesh.positions, testing::frames_of(seq.garments[0].positions, seq.n_frames, 1, 1));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/s_body.pc2")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/s_jacket.pc2")));
}

// Reads a GLB back by hand (header, JSON and BIN chunks) and rebuilds each
// frame of a node's mesh from its base and morph targets as the weights
// animation's keyframes select them.
struct GlbReadBack {
  nlohmann::json doc;
  std::string bin;
  explicit GlbReadBack(const std::string& bytes) {
    const auto u32 = [&](std::size_t at) {
      std::uint32_t v = 0;
      std::memcpy(&v, bytes.data() + at, 4);
      return v;
    };
    EXPECT_EQ(u32(0), 0x46546C67u) << "magic glTF";
    EXPECT_EQ(u32(4), 2u);
    EXPECT_EQ(u32(8), bytes.size());
    const std::uint32_t json_length = u32(12);
    EXPECT_EQ(u32(16), 0x4E4F534Au);
    doc = nlohmann::json::parse(bytes.substr(20, json_length));
    const std::size_t bin_at = 20 + json_length;
    EXPECT_EQ(u32(bin_at + 4), 0x004E4942u);
    bin = bytes.substr(bin_at + 8, u32(bin_at));
  }
  std::vector<float> floats(int accessor) const {
    const auto& a = doc["accessors"][accessor];
    const auto& v = doc["bufferViews"][a["bufferView"].get<int>()];
    const int per = a["type"] == "VEC3" ? 3 : 1;
    std::vector<float> out(a["count"].get<std::size_t>() * per);
    std::memcpy(out.data(), bin.data() + v["byteOffset"].get<std::size_t>(), out.size() * sizeof(float));
    return out;
  }
  // STEP sampling: the index of the last keyframe of `sampler` at or before time t.
  std::size_t keyframe(const nlohmann::json& sampler, float t) const {
    const std::vector<float> times = floats(sampler["input"].get<int>());
    std::size_t j = 0;
    while (j + 1 < times.size() && times[j + 1] <= t + 1e-6f) ++j;
    return j;
  }
  const nlohmann::json* channel(int node, const std::string& path) const {
    for (const auto& c : doc["animations"][0]["channels"])
      if (c["target"]["node"] == node && c["target"]["path"] == path)
        return &doc["animations"][0]["samplers"][c["sampler"].get<int>()];
    return nullptr;
  }
  bool visible(int node, float t) const {
    const nlohmann::json* s = channel(node, "scale");
    if (!s) return !doc["nodes"][node].contains("scale");
    return floats((*s)["output"].get<int>())[3 * keyframe(*s, t)] > 0;
  }
  // Positions of the mesh named `name` at frame k (30 fps from the first
  // exported frame): its node, or the chunk node visible then.
  std::vector<float> frame(const std::string& name, std::size_t k) const {
    const float t = static_cast<float>(k) / 30.0f;
    for (int n = 0; n < static_cast<int>(doc["nodes"].size()); ++n) {
      if (doc["nodes"][n]["name"] != name) continue;
      std::vector<int> nodes = {n};
      if (doc["nodes"][n].contains("children")) nodes = doc["nodes"][n]["children"].get<std::vector<int>>();
      for (int c : nodes)
        if (visible(c, t)) return mesh_at(c, t);
    }
    ADD_FAILURE() << "no visible node " << name << " at frame " << k;
    return {};
  }
  std::vector<float> mesh_at(int n, float t) const {
    const auto& prim = doc["meshes"][doc["nodes"][n]["mesh"].get<int>()]["primitives"][0];
    std::vector<float> p = floats(prim["attributes"]["POSITION"].get<int>());
    const nlohmann::json* sampler = channel(n, "weights");
    if (!sampler) return p;
    const std::vector<float> weights = floats((*sampler)["output"].get<int>());
    const std::size_t targets = prim["targets"].size(), j = keyframe(*sampler, t);
    for (std::size_t i = 0; i < targets; ++i) {
      const float w = weights[j * targets + i];
      if (w == 0) continue;
      const std::vector<float> d = floats(prim["targets"][i]["POSITION"].get<int>());
      for (std::size_t v = 0; v < p.size(); ++v) p[v] += w * d[v];
    }
    return p;
  }
};

TEST_F(DataExport, GlbPlaysEveryFrameAsMorphTargets) {
  const Dataset ds = Dataset::open(dir.file("ds"));
  const auto files = export_sequence(ds, "s", parse_export_format("glb"), 2, 7, dir.file("out"));
  ASSERT_EQ(files, (std::vector<std::string>{dir.file("out/s.glb")}));
  const GlbReadBack glb(test::read_bytes(files[0]));
  ASSERT_EQ(glb.doc["nodes"].size(), 3u);  // body, tshirt, jacket
  EXPECT_EQ(glb.doc["nodes"][1]["name"], "tshirt");
  const std::vector<float> times = glb.floats(glb.doc["animations"][0]["samplers"][0]["input"].get<int>());
  ASSERT_EQ(times.size(), 5u);
  EXPECT_FLOAT_EQ(times[4], 4.0f / 30.0f);  // the format's 30 fps
  for (std::size_t k = 0; k < 5; ++k) {
    const std::vector<float> body = glb.frame("body", k), jacket = glb.frame("jacket", k);
    const std::vector<float> body_truth = testing::frames_of(seq.body.positions, seq.n_frames, 2 + k, 1);
    const std::vector<float> jacket_truth = testing::frames_of(seq.garments[1].positions, seq.n_frames, 2 + k, 1);
    ASSERT_EQ(body.size(), body_truth.size());
    ASSERT_EQ(jacket.size(), jacket_truth.size());
    for (std::size_t i = 0; i < body.size(); ++i) EXPECT_NEAR(body[i], body_truth[i], 1e-5) << k;
    for (std::size_t i = 0; i < jacket.size(); ++i) EXPECT_NEAR(jacket[i], jacket_truth[i], 1e-5) << k;
  }
  // The validator's asks: every vertex buffer view has a target, every
  // POSITION accessor its bounds.
  for (const auto& m : glb.doc["meshes"]) {
    const auto& prim = m["primitives"][0];
    EXPECT_TRUE(glb.doc["accessors"][prim["attributes"]["POSITION"].get<int>()].contains("min"));
    EXPECT_EQ(
        glb.doc["bufferViews"][glb.doc["accessors"][prim["indices"].get<int>()]["bufferView"].get<int>()]["target"],
        34963);
  }
}

// The Khronos validator (npm gltf-validator, installed by scripts/setup.sh
// in tests/browser): no error, warning, info or hint.
// A long sequence in chunks: each mesh a parent node with one child per
// chunk, one child shown at a time, every frame as stored, and the weights
// linear in the frames.
TEST_F(DataExport, GlbCutsLongSequencesIntoChunks) {
  const Dataset ds = Dataset::open(dir.file("ds"));
  const auto files = export_sequence(ds, "s", ExportFormat::Glb, 0, 12, dir.file("out"), 5);
  const GlbReadBack glb(test::read_bytes(files.at(0)));
  ASSERT_EQ(glb.doc["nodes"].size(), 12u);  // 3 meshes x (3 chunks + a parent)
  ASSERT_EQ(glb.doc["scenes"][0]["nodes"].size(), 3u);
  const auto& tshirt = glb.doc["nodes"][glb.doc["scenes"][0]["nodes"][1].get<int>()];
  EXPECT_EQ(tshirt["name"], "tshirt");
  EXPECT_EQ(tshirt["children"].size(), 3u);
  std::size_t weights = 0;
  for (const auto& sampler : glb.doc["animations"][0]["samplers"])
    if (glb.doc["accessors"][sampler["output"].get<int>()]["type"] == "SCALAR")
      weights += glb.doc["accessors"][sampler["output"].get<int>()]["count"].get<std::size_t>();
  EXPECT_EQ(weights, 3u * (5 * 4 + 5 * 4 + 2 * 1));  // not 3 x 12 x 11
  for (std::size_t k = 0; k < 12; ++k) {
    int shown = 0;
    for (int c : tshirt["children"]) shown += glb.visible(c, static_cast<float>(k) / 30.0f);
    EXPECT_EQ(shown, 1) << "frame " << k;
    const std::vector<float> got = glb.frame("tshirt", k);
    const std::vector<float> want = testing::frames_of(seq.garments[0].positions, seq.n_frames, k, 1);
    ASSERT_EQ(got.size(), want.size());
    for (std::size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], want[i], 1e-5) << k;
  }
}

TEST_F(DataExport, GlbPassesTheKhronosValidator) {
  if (const std::string missing = test::gltf_validator_missing(); !missing.empty()) GTEST_SKIP() << missing;
  const Dataset ds = Dataset::open(dir.file("ds"));
  for (const std::int64_t chunk : {kGlbFramesPerChunk, std::int64_t{5}}) {
    const std::string out = dir.file("out" + std::to_string(chunk));
    const auto files = export_sequence(ds, "s", ExportFormat::Glb, 0, 12, out, chunk);
    const test::GltfReport report = test::validate_gltf(files.at(0));
    EXPECT_TRUE(report.clean()) << report.output;
  }
}

TEST(MeshFileNames, DistinctAndFileSafeWithTheBodyFirst) {
  EXPECT_EQ(mesh_file_names({"body", "my dress", "", "my_dress", "../x"}),
            (std::vector<std::string>{"body", "body_2", "my_dress", "garment2", "my_dress_2", "___x"}));
}

TEST_F(DataExport, BadRangeAndFormat) {
  const Dataset ds = Dataset::open(dir.file("ds"));
  const std::string e =
      test::error_of<InputError>([&] { export_sequence(ds, "s", ExportFormat::Obj, 5, 20, dir.file("out")); });
  EXPECT_NE(e.find("expected [first,last) with 0 <= first < last <= 12, got [5,20)"), std::string::npos) << e;
  EXPECT_NE(test::error_of<InputError>([&] { parse_export_format("fbx"); }).find("expected obj, pc2 or glb, got 'fbx'"),
            std::string::npos);
}

}  // namespace
}  // namespace layers::data
