// tests/adversarial/test_adversarial_imports.cpp -- issue 62's cases of
// the import doors through the `layers` binary, as a user would meet them:
// garment files and side files that declare or nest far more than they
// hold, or are not what their name says (M1, M2, messages 1, 4, 5, 9),
// and a config of millions of values (M3). Each ends with exit 1, one line
// naming the file and what is wrong, within 1 GiB of peak memory, and
// writes nothing; the same scene with well-formed files is made.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>

#include "layers/data/glb.h"
#include "probe.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace fs = std::filesystem;
using namespace layers;

namespace {

using test::kMaxPeakMiB;
using test::probe;

class Imports : public ::testing::Test {
 protected:
  // Our templates' dress and jacket as OBJ files (coarse), once.
  static void SetUpTestSuite() {
    root_ = new test::TempDir("layers-imports");
    const test::Probe p = probe("tpose" + scene("[{inner: [dress], outer: jacket}]") + " --out " + root_->file("mine"),
                                root_->file("tpose.log"));
    ASSERT_EQ(p.exit_code, 0) << p.output;
  }
  static void TearDownTestSuite() {
    delete root_;
    root_ = nullptr;
  }
  static std::string scene(const std::string& outfits) {
    return " --config " + test::source_dir() +
           "/configs/data/tiny.yaml --set frames=3 --set drape_frames=2 --set body.transition_frames=2"
           " --set garments.fit.edge_length=0.1 --set 'garments.outfits=" +
           outfits + "'";
  }
  // `inner` as the dress of a tpose: refused with one line holding
  // `expect`, within the memory bound, nothing written.
  void refused(const std::string& inner, const std::string& expect) {
    const std::string out = dir_.file("out-" + std::to_string(++runs_));
    const std::string outfit =
        "[{inner: [\"file:" + inner + "\"], outer: \"file:" + root_->file("mine/jacket.obj") + "\"}]";
    const test::Probe p = probe("tpose" + scene(outfit) + " --out " + out, dir_.file("log-" + std::to_string(runs_)));
    EXPECT_EQ(p.exit_code, 1) << inner << "\n" << p.output;
    EXPECT_EQ(std::count(p.output.begin(), p.output.end(), '\n'), 1) << p.output;
    EXPECT_NE(p.output.find(expect), std::string::npos) << p.output;
    EXPECT_LT(p.peak_mib, kMaxPeakMiB) << inner;
    EXPECT_FALSE(fs::exists(out)) << "a refused command wrote " << out;
  }
  std::string write(const std::string& name, const std::string& bytes) {
    const std::string path = dir_.file(name);
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }
  static test::TempDir* root_;
  test::TempDir dir_{"layers-imports-case"};
  int runs_ = 0;
};
test::TempDir* Imports::root_ = nullptr;

TEST_F(Imports, WellFormedFilesAreMade) {
  const std::string out = dir_.file("fine");
  const std::string outfit = "[{inner: [\"file:" + root_->file("mine/dress.obj") +
                             "\"], outer: \"file:" + root_->file("mine/jacket.obj") + "\"}]";
  const test::Probe p = probe("tpose" + scene(outfit) + " --out " + out, dir_.file("fine.log"));
  EXPECT_EQ(p.exit_code, 0) << p.output;
  EXPECT_LT(p.peak_mib, kMaxPeakMiB);
  EXPECT_TRUE(fs::exists(out + "/dress.obj"));
}

// M1 and message 5: a 227-byte binary PLY declaring 2,000,000,000 vertices
// (23.5 GB before assimp's "File corrupted"); message 9: a binary STL
// declaring 2^31 facets.
TEST_F(Imports, DeclaredCountsBeyondTheFile) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 2000000000\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  refused(write("g.ply", header + std::string(227 - header.size(), '\0')),
          "g.ply: element vertex: expected at most 4 (what the 227-byte file has room for");
  std::string stl(80, ' ');
  const std::uint32_t facets = 2147483648u;
  stl.append(reinterpret_cast<const char*>(&facets), 4);
  stl.append(100, '\0');
  refused(write("g.stl", stl), "g.stl: facet count: expected at most 2 facets");
}

// Message 4: a GLB whose JSON chunk is not JSON.
TEST_F(Imports, AGlbWithBrokenJson) {
  const std::vector<float> xyz = {0, 0, 0, 0.3f, 0, 0, 0.3f, 0.3f, 0};
  std::string glb = data::glb_bytes({data::GlbMesh{"tri", {0, 1, 2}, {xyz, xyz}}}, 30.0);
  glb[20] = 'x';
  refused(write("g.glb", glb), "g.glb: GLB JSON chunk: expected valid JSON, got [json.exception.parse_error");
}

// M2 and messages 1-2: side files of 5 million list items (20 MB: 4.78 GB
// before), a NUL byte, 100,000 levels of nesting.
TEST_F(Imports, SideFilesBoundedLikeConfigs) {
  fs::copy_file(root_->file("mine/dress.obj"), dir_.file("dress.obj"));
  std::string many = "name: dress\nnotes:\n";
  for (int i = 0; i < 5000000; ++i) many += "- x\n";
  write("dress.yaml", many);
  refused(dir_.file("dress.obj"), "dress.yaml:");
  refused(dir_.file("dress.obj"), "expected YAML of at most 1000000 values");
  write("dress.yaml", std::string("name: \"a\0i\"\n", 12));
  refused(dir_.file("dress.obj"), "dress.yaml:1: expected YAML text, got a NUL byte (a binary file?) at byte 8");
  write("dress.yaml", "a: " + std::string(100000, '['));
  refused(dir_.file("dress.obj"), "dress.yaml:1: expected values nested at most 64 levels deep");
}

// M3: a 16 MB config of 4 million list items (2.29 GB and 9.7 s before
// its line); counted while parsing.
TEST_F(Imports, AConfigOfMillionsOfValues) {
  std::string big = "run: {seed: 0}\nlist:\n";
  for (int i = 0; i < 4000000; ++i) big += "- 1\n";
  const std::string path = write("big.yaml", big);
  const test::Probe p = probe("config " + path, dir_.file("big.log"));
  EXPECT_EQ(p.exit_code, 1) << p.output;
  EXPECT_NE(p.output.find("big.yaml:"), std::string::npos) << p.output;
  EXPECT_NE(p.output.find("expected YAML of at most 1000000 values"), std::string::npos) << p.output;
  EXPECT_LT(p.peak_mib, kMaxPeakMiB);
}

}  // namespace
