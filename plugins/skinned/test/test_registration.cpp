// The built "skinned" plugin registers "skinned", and
// configs/models/skinned.yaml creates it. Torch-free (the model is only
// created and dropped here).
#include "model_plugin.h"
#include "spec.h"

TEST(ReferencePlugins, SkinnedPluginAndConfig) {
  layers::test::expect_plugin_and_config(layers::reference::kSkinned.name, layers::reference::kSkinned.description);
}
