// tests/support/model_plugin.h -- the check that a built model plugin (in
// plugins/ beside the layers binary) registers its model with its
// description, and that its config in configs/models creates it.
#pragma once

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "layers/core/config_node.h"
#include "layers/zoo/model_config.h"
#include "layers/zoo/plugin_loader.h"
#include "layers/zoo/registry.h"
#include "test_paths.h"

namespace layers::test {

// The real plugins sit in plugins/ next to the layers binary.
inline std::string real_plugin(const std::string& name) {
  return (std::filesystem::path(layers_bin()).parent_path() / "plugins" / ("liblayers_plugin_" + name + ".so"))
      .string();
}

inline void expect_plugin_and_config(const std::string& name, const std::string& description) {
  zoo::Registry registry;
  zoo::LoadedPlugin loaded = zoo::load_file(registry, real_plugin(name));
  ASSERT_EQ(loaded.models, std::vector<std::string>{name});
  ASSERT_NE(registry.find(name), nullptr);
  EXPECT_EQ(registry.find(name)->description, description);

  cfg::Node root = cfg::load_file(source_dir() + "/configs/models/" + name + ".yaml");
  const cfg::Node* section = root.find("model");
  ASSERT_NE(section, nullptr);
  EXPECT_NE(zoo::create_model(registry, *section), nullptr);
}

}  // namespace layers::test
