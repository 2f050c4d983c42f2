// A body as a skinned, animated glTF rig (data/skinned_glb.h) on the tiny
// rig (tests/support/tiny_rig.h): the document's joints, skin and
// animation, refusals of a joint listed before its parent and of a single
// frame, and npm's gltf-validator finding nothing to report. (Read back by
// assimp frame by frame: tests/unit/import/test_body_import.cpp.)
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "error_of.h"
#include "gltf_validator.h"
#include "layers/core/error.h"
#include "layers/data/skinned_glb.h"
#include "temp_dir.h"
#include "tiny_rig.h"

namespace layers::data {
namespace {

nlohmann::json document(const std::string& glb) {
  std::uint32_t length = 0;
  std::memcpy(&length, glb.data() + 12, 4);
  return nlohmann::json::parse(glb.substr(20, length));
}

TEST(SkinnedGlb, JointsSkinAndOneSamplerPerJoint) {
  const test::TinyRig rig(4);
  const nlohmann::json doc = document(skinned_glb_bytes(rig.body, 30.0));
  ASSERT_EQ(doc["nodes"].size(), 4u);  // three joints, the mesh
  EXPECT_EQ(doc["nodes"][0]["name"], "mixamorig:Hips");
  EXPECT_EQ(doc["nodes"][0]["children"], nlohmann::json::array({1}));
  EXPECT_NEAR(doc["nodes"][1]["translation"][1].get<double>(), 0.25, 1e-6);  // its offset from the hips
  EXPECT_EQ(doc["nodes"][3]["skin"], 0);
  EXPECT_EQ(doc["skins"][0]["joints"].size(), 3u);
  const auto& animation = doc["animations"][0];
  EXPECT_EQ(animation["name"], "motion");
  EXPECT_EQ(animation["channels"].size(), 4u);  // a rotation per joint, the root's translation
  const int input = animation["samplers"][0]["input"];
  EXPECT_EQ(doc["accessors"][input]["count"], 4);
  EXPECT_NEAR(doc["accessors"][input]["max"][0].get<double>(), 0.1, 1e-6);
}

TEST(SkinnedGlb, AChildBeforeItsParentOrOneFrameIsRefused) {
  test::TinyRig rig(2);
  rig.body.joint_parents = {-1, 2, 0};
  EXPECT_NE(test::error_of<Error>([&] { skinned_glb_bytes(rig.body, 30.0); }).find("joint 1 has parent 2"),
            std::string::npos);
  test::TinyRig one(1);
  EXPECT_NE(test::error_of<Error>([&] { skinned_glb_bytes(one.body, 30.0); }).find("at least 2 frames"),
            std::string::npos);
}

TEST(SkinnedGlb, PassesTheKhronosValidator) {
  if (const std::string missing = test::gltf_validator_missing(); !missing.empty()) GTEST_SKIP() << missing;
  test::TempDir dir("skinned_glb");
  const std::string path = dir.file("rig.glb");
  std::ofstream(path, std::ios::binary) << skinned_glb_bytes(test::TinyRig(5).body, 30.0);
  const test::GltfReport report = test::validate_gltf(path);
  EXPECT_TRUE(report.clean()) << report.output;
}

}  // namespace
}  // namespace layers::data
