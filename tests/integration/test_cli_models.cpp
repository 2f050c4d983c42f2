// `layers models` and model sections of configs, with the test plugins of
// tests/plugins found through LAYERS_PLUGIN_PATH.
#include <gtest/gtest.h>

#include <filesystem>

#include "run_command.h"
#include "temp_dir.h"

using namespace layers;
using test::run_command;

namespace {
std::string with_test_plugins(const std::string& args) {
  return "LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin() + " " + args;
}
}  // namespace

TEST(CliModels, ListsTestPluginLoadedThroughDlopen) {
  auto r = run_command(with_test_plugins("models"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("test_constant_velocity"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("liblayers_plugin_test_constant_velocity.so"), std::string::npos) << r.output;
  // The deliberately broken plugins are refused with their reasons.
  EXPECT_NE(r.output.find("built for zoo API v999, this layers expects v2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("no entry point"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("registered twice"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("expected a function symbol, got a data object"), std::string::npos) << r.output;
  auto strict = run_command(with_test_plugins("models --strict"));
  EXPECT_EQ(strict.exit_code, 1) << strict.output;
}

TEST(CliModels, StrictRefusesPluginBuiltAgainstAnotherLibTorch) {
  test::TempDir dir;
  // Only the mismatched plugin on the path, so --strict fails because of it.
  std::filesystem::copy_file(test::plugin_dir() + "/liblayers_plugin_test_wrong_abi.so",
                             dir.path() + "/liblayers_plugin_test_wrong_abi.so");
  auto r = run_command("LAYERS_PLUGIN_PATH=" + dir.path() + " " + test::layers_bin() + " models --strict");
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(r.output.find("liblayers_plugin_test_wrong_abi.so: built against LibTorch 0.4.1, this layers uses "),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("rebuild the plugin against this layers"), std::string::npos) << r.output;
}

TEST(CliModels, ConfigChecksModelNameAndParameters) {
  test::TempDir dir;
  std::string good = dir.write("good.yaml", "model:\n  name: test_constant_velocity\n  params: {damping: 0.25}\n");
  auto ok = run_command(with_test_plugins("config " + good));
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_NE(ok.output.find("damping: 0.25"), std::string::npos) << ok.output;

  std::string unknown = dir.write("unknown.yaml", "run: {seed: 1}\nmodel:\n  name: layersnet_typo\n");
  auto u = run_command(with_test_plugins("config " + unknown));
  EXPECT_EQ(u.exit_code, 1) << u.output;
  EXPECT_NE(u.output.find("unknown.yaml:3: model.name: unknown model 'layersnet_typo'"), std::string::npos) << u.output;
  EXPECT_NE(u.output.find("registered models: "), std::string::npos) << u.output;
  EXPECT_NE(u.output.find("test_constant_velocity ("), std::string::npos) << u.output;

  std::string bad = dir.write("bad.yaml", "model:\n  name: test_constant_velocity\n  params:\n    damping: 3\n");
  auto b = run_command(with_test_plugins("config " + bad));
  EXPECT_EQ(b.exit_code, 1) << b.output;
  EXPECT_NE(b.output.find("bad.yaml:4: model.params.damping"), std::string::npos) << b.output;

  // (With no plugin at all the message says where plugins are searched:
  // test_registry covers it; the real plugins sit beside this binary.)
}
