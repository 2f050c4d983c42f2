// motion::clip_folder_entries: a folder of clips read as a motion library
// (its .bvh and .amc files, by name), and what is not one.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include <unistd.h>

#include "layers/core/error.h"
#include "layers/motion/motion.h"

namespace layers::motion {
namespace {

namespace fs = std::filesystem;

class ClipFolder : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("layers_clip_folder_" + std::to_string(::getpid()));
    fs::create_directories(dir_ / "lib" / "nested");
    fs::create_directories(dir_ / "empty");
    for (const char* name : {"b_walk.bvh", "a_jump.BVH", "c_run.amc", "c_run.asf", "notes.txt", "nested/d.bvh"})
      std::ofstream(dir_ / "lib" / name) << "x";
  }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ClipFolder, ListsTheClipsByNameAsTheEntryNamesTheFolder) {
  const std::string lib = (dir_ / "lib").string();
  const std::vector<std::string> want{lib + "/a_jump.BVH", lib + "/b_walk.bvh", lib + "/c_run.amc"};
  EXPECT_EQ(clip_folder_entries(lib, "test"), want);
  EXPECT_EQ(clip_folder_entries(lib + "/", "test"), want);
  const std::vector<std::string> prefixed = clip_folder_entries("bvh:" + lib, "test");
  ASSERT_EQ(prefixed.size(), 3u);
  EXPECT_EQ(prefixed[0], "bvh:" + lib + "/a_jump.BVH");
}

TEST_F(ClipFolder, AClipOrAProceduralEntryIsNotAFolder) {
  EXPECT_TRUE(clip_folder_entries((dir_ / "lib" / "b_walk.bvh").string(), "test").empty());
  EXPECT_TRUE(clip_folder_entries("procedural:walk", "test").empty());
  EXPECT_TRUE(clip_folder_entries((dir_ / "missing").string(), "test").empty());
  EXPECT_TRUE(clip_folder_entries((dir_ / "lib").string() + " window=0+30", "test").empty());
}

TEST_F(ClipFolder, AFolderWithoutClipsIsRefusedByName) {
  try {
    clip_folder_entries((dir_ / "empty").string(), "cfg.yaml: body.motions[1]");
    FAIL() << "an empty folder was taken";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cfg.yaml: body.motions[1]"), std::string::npos) << what;
    EXPECT_NE(what.find("at least one .bvh or .amc clip"), std::string::npos) << what;
  }
}

TEST(ClipFolderShipped, TheCmuLibraryIsAFolderInsideTheAssets) {
  const std::vector<std::string> clips = clip_folder_entries("cmu/library", "test");
  ASSERT_EQ(clips.size(), 10u);
  EXPECT_EQ(clips.front(), "cmu/library/01_01.bvh");
  EXPECT_EQ(clips.back(), "cmu/library/03_03.bvh");
}

}  // namespace
}  // namespace layers::motion
