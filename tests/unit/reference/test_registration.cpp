// The built reference plugins register "static" and "skinned", and the
// configs in configs/models create them. Torch-free (the models are only
// created and dropped here).
#include <gtest/gtest.h>

#include <filesystem>

#include "layers/core/config_node.h"
#include "layers/zoo/model_config.h"
#include "layers/zoo/plugin_loader.h"
#include "layers/zoo/registry.h"
#include "skinned_model.h"
#include "static_model.h"
#include "test_paths.h"

namespace zoo = layers::zoo;
namespace cfg = layers::cfg;
namespace fs = std::filesystem;

namespace {

// The real plugins sit in plugins/ next to the layers binary.
std::string real_plugin(const std::string& name) {
  return (fs::path(layers::test::layers_bin()).parent_path() / "plugins" / ("liblayers_plugin_" + name + ".so"))
      .string();
}

void expect_plugin_and_config(const std::string& name, const std::string& description) {
  zoo::Registry registry;
  zoo::LoadedPlugin loaded = zoo::load_file(registry, real_plugin(name));
  ASSERT_EQ(loaded.models, std::vector<std::string>{name});
  ASSERT_NE(registry.find(name), nullptr);
  EXPECT_EQ(registry.find(name)->description, description);

  cfg::Node root = cfg::load_file(layers::test::source_dir() + "/configs/models/" + name + ".yaml");
  const cfg::Node* section = root.find("model");
  ASSERT_NE(section, nullptr);
  EXPECT_NE(zoo::create_model(registry, *section), nullptr);
}

}  // namespace

TEST(ReferencePlugins, StaticPluginAndConfig) {
  expect_plugin_and_config(layers::reference::kStaticName, layers::reference::kStaticDescription);
}

TEST(ReferencePlugins, SkinnedPluginAndConfig) {
  expect_plugin_and_config(layers::reference::kSkinnedName, layers::reference::kSkinnedDescription);
}
