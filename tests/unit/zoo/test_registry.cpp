// Registry: names, duplicates, unknown models.
#include <gtest/gtest.h>

#include "error_of.h"
#include "layers/core/config_node.h"
#include "layers/core/error.h"
#include "layers/zoo/registry.h"

using layers::zoo::Registry;

namespace {

layers::zoo::ModelFactory null_factory() {
  return [](const layers::cfg::Node&) { return std::shared_ptr<layers::zoo::Model>(); };
}

}  // namespace

TEST(Registry, NamesAreSortedAndEntriesKeepPaths) {
  Registry r;
  r.add("mgnet", "uv model", null_factory(), "/p/liblayers_plugin_mgnet.so");
  r.add("deepsd", "skinning model", null_factory());
  EXPECT_EQ(r.names(), (std::vector<std::string>{"deepsd", "mgnet"}));
  ASSERT_NE(r.find("mgnet"), nullptr);
  EXPECT_EQ(r.find("mgnet")->plugin_path, "/p/liblayers_plugin_mgnet.so");
  EXPECT_EQ(r.find("deepsd")->plugin_path, "<built-in>");
  EXPECT_EQ(r.entries().at(1).description, "uv model");
  EXPECT_TRUE(r.contains("deepsd"));
  EXPECT_EQ(r.find("layersnet"), nullptr);
}

TEST(Registry, DuplicateNamesBothFiles) {
  Registry r;
  r.add("layersnet", "", null_factory(), "/a/liblayers_plugin_layersnet.so");
  EXPECT_EQ(layers::test::error_of([&] { r.add("layersnet", "", null_factory(), "/b/liblayers_plugin_other.so"); }),
            "/b/liblayers_plugin_other.so: model 'layersnet': registered twice: by "
            "/a/liblayers_plugin_layersnet.so and by /b/liblayers_plugin_other.so; model names must be "
            "unique, remove or rename one of the plugins");
  EXPECT_EQ(r.find("layersnet")->plugin_path, "/a/liblayers_plugin_layersnet.so");
}

TEST(Registry, RejectsBadNamesAndMissingFactories) {
  Registry r;
  EXPECT_THROW(r.add("", "", null_factory()), layers::InputError);
  EXPECT_THROW(r.add("has space", "", null_factory()), layers::InputError);
  EXPECT_THROW(r.add("ok", "", nullptr), layers::Error);
  EXPECT_TRUE(r.names().empty());
}

TEST(Registry, UnknownModelListsRegisteredOnes) {
  Registry r;
  r.add("static", "", null_factory(), "/x/liblayers_plugin_static.so");
  r.add("skinned", "", null_factory(), "/x/liblayers_plugin_skinned.so");
  layers::cfg::Node params = layers::cfg::parse("a: 1\n", "exp.yaml");
  try {
    r.create("layersnet", params);
    FAIL() << "no error";
  } catch (const layers::InputError& e) {
    EXPECT_STREQ(e.what(),
                 "exp.yaml: model: unknown model 'layersnet'; registered models: skinned "
                 "(/x/liblayers_plugin_skinned.so), static (/x/liblayers_plugin_static.so)");
  }
}

TEST(Registry, UnknownModelWithNothingRegistered) {
  Registry r;
  std::string message = layers::test::error_of([&] { r.create("layersnet", layers::cfg::Node{}); });
  EXPECT_NE(message.find("unknown model 'layersnet'; no models registered; check LAYERS_PLUGIN_PATH"),
            std::string::npos)
      << message;
}

TEST(Registry, FactoryReturningNothingIsAnError) {
  Registry r;
  r.add("empty", "", null_factory(), "/x/liblayers_plugin_empty.so");
  EXPECT_EQ(layers::test::error_of([&] { r.create("empty", layers::cfg::Node{}); }),
            "/x/liblayers_plugin_empty.so: the factory of model 'empty' returned no model");
}
