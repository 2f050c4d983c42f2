// same_saved_config (libs/generate/generator_config.h): a dataset folder's
// saved generator.yaml against the config a run resolved. A file written
// before a setting existed is the same config when the setting's default
// is what the run asks for, and not when it asks for something else.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include <unistd.h>

#include "layers/core/atomic_file.h"
#include "layers/core/config_node.h"
#include "layers/generate/generator_config.h"

namespace layers::generate {
namespace {

namespace fs = std::filesystem;

std::string resolved(const GeneratorConfig& c) { return cfg::to_yaml(cfg::to_node(c)); }

// `text` with the line that holds `key` removed.
std::string without_line(const std::string& text, const std::string& key) {
  const auto at = text.find(key);
  if (at == std::string::npos) return text;
  const auto start = text.rfind('\n', at) + 1;
  const auto end = text.find('\n', at);
  return text.substr(0, start) + text.substr(end + 1);
}

class SavedConfig : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("layers_saved_config_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string save(const std::string& text) {
    const std::string path = (dir_ / "generator.yaml").string();
    write_text_atomic(path, text);
    return path;
  }
  fs::path dir_;
};

TEST_F(SavedConfig, TheSameTextIsTheSameConfig) {
  GeneratorConfig c;
  c.sequences = 12;
  EXPECT_TRUE(same_saved_config(save(resolved(c)), resolved(c)));
  GeneratorConfig other = c;
  other.sequences = 13;
  EXPECT_FALSE(same_saved_config(save(resolved(c)), resolved(other)));
}

TEST_F(SavedConfig, ASettingAddedLaterCountsAtItsDefault) {
  GeneratorConfig c;  // hip_room off, its default
  const std::string before = without_line(resolved(c), "hip_room:");
  ASSERT_EQ(before.find("hip_room"), std::string::npos);
  ASSERT_NE(before, resolved(c));
  EXPECT_TRUE(same_saved_config(save(before), resolved(c)));
  // A run that asks for hip room is not what the old folder was made with.
  GeneratorConfig roomy = c;
  roomy.garments.hip_room = true;
  EXPECT_FALSE(same_saved_config(save(before), resolved(roomy)));
}

TEST_F(SavedConfig, AFileWithoutTheMaterialMappingHasTheDefaultOne) {
  GeneratorConfig c;
  std::string before = resolved(c);
  for (const char* key : {"material:", "density_per_mass:", "modulus_per_stiffness:", "compression_per_stiffness:",
                          "shear_per_stiffness:", "rigidity_per_bending:", "friction_per_unit:"})
    before = without_line(before, key);
  ASSERT_EQ(before.find("rigidity_per_bending"), std::string::npos);
  EXPECT_TRUE(same_saved_config(save(before), resolved(c)));
  GeneratorConfig stiffer = c;
  stiffer.garments.material.compression_per_stiffness *= 4;
  EXPECT_FALSE(same_saved_config(save(before), resolved(stiffer)));
}

TEST_F(SavedConfig, AFileTheSchemaRejectsIsNotTheSame) {
  GeneratorConfig c;
  EXPECT_FALSE(same_saved_config(save(resolved(c) + "no_such_setting: 3\n"), resolved(c)));
  EXPECT_FALSE(same_saved_config(save("sequences: [\n"), resolved(c)));
}

}  // namespace
}  // namespace layers::generate
