// The built "static" plugin registers "static", and configs/models/static.yaml
// creates it. Torch-free (the model is only created and dropped here).
#include "model_plugin.h"
#include "spec.h"

TEST(ReferencePlugins, StaticPluginAndConfig) {
  layers::test::expect_plugin_and_config(layers::reference::kStatic.name, layers::reference::kStatic.description);
}
