// `cmake --install` end to end: the build is installed into a temporary
// prefix, the prefix is moved elsewhere, and the installed `layers` finds
// its plugins (<prefix>/lib/layers/plugins) and assets
// (<prefix>/share/layers/assets) relative to itself: it lists the models
// and generates a tiny dataset from the installed configs.
#include <gtest/gtest.h>

#include <filesystem>

#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

// Runs the installed binary with no override of its search paths.
test::CommandResult installed(const std::string& prefix, const std::string& args) {
  return run_command("env -u LAYERS_PLUGIN_PATH -u LAYERS_ASSETS " + prefix + "/bin/layers " + args);
}

}  // namespace

TEST(Install, PrefixIsSelfContainedAndRelocatable) {
  test::TempDir dir("layers-install");
  const std::string first = dir.file("first-prefix");
  auto inst = run_command("'" LAYERS_TEST_CMAKE "' --install '" LAYERS_TEST_BUILD_DIR "' --prefix " + first);
  ASSERT_EQ(inst.exit_code, 0) << inst.output;
  // Move the prefix: nothing may point back at where it was installed.
  const std::string prefix = dir.file("moved/prefix");
  fs::create_directories(dir.file("moved"));
  fs::rename(first, prefix);
  for (const char* f : {"bin/layers", "share/layers/assets/body/mpfb2/base.obj",
                        "share/layers/assets/motions/cmu/131_01_start_walk_stop.bvh",
                        "share/layers/configs/data/tiny.yaml", "lib/layers/plugins/liblayers_plugin_static.so",
                        // Its content hash, recorded after install rewrote its RPATH (`models --strict`
                        // below refuses a plugin that does not match it), and the tool that records it.
                        "lib/layers/plugins/liblayers_plugin_static.so.hash", "bin/layers_plugin_hash"})
    EXPECT_TRUE(fs::exists(prefix + "/" + f)) << f;

  // Plugins: found beside the installed binary, not in the build tree.
  auto models = installed(prefix, "models --strict");
  ASSERT_EQ(models.exit_code, 0) << models.output;
  EXPECT_NE(models.output.find(prefix + "/lib/layers/plugins/liblayers_plugin_static.so"), std::string::npos)
      << models.output;
  EXPECT_NE(models.output.find("skinned"), std::string::npos) << models.output;
  EXPECT_EQ(models.output.find(LAYERS_TEST_BUILD_DIR), std::string::npos) << models.output;

  // A tiny generate from the installed configs, run from an unrelated folder.
  const std::string cfg = prefix + "/share/layers/configs/data/tiny.yaml";
  const std::string args = "generate --config " + cfg +
                           " --quiet --set sequences=3 --set frames=4 --set drape_frames=2"
                           " --set body.transition_frames=2 --set garments.fit.edge_length=0.1"
                           " --set sim.validation.max_l_penetration=1 --set sim.validation.max_h_penetration=1"
                           " --set sim.validation.max_stretch=100 --set sim.validation.max_h_crossing_clear=1";
  auto gen = run_command("cd " + dir.path() + " && env -u LAYERS_PLUGIN_PATH -u LAYERS_ASSETS " + prefix +
                         "/bin/layers " + args + " --out " + dir.file("ds"));
  ASSERT_EQ(gen.exit_code, 0) << gen.output;
  EXPECT_TRUE(fs::exists(dir.file("ds/dataset.yaml")));
  auto valid = installed(prefix, "validate " + dir.file("ds"));
  EXPECT_EQ(valid.exit_code, 0) << valid.output;

  // The body really comes from the prefix: without its mesh there, the
  // same generate fails and names the installed file.
  fs::remove(prefix + "/share/layers/assets/body/mpfb2/base.obj");
  auto broken = installed(prefix, args + " --out " + dir.file("ds2"));
  EXPECT_NE(broken.exit_code, 0) << broken.output;
  EXPECT_NE(broken.output.find(prefix + "/share/layers/assets/body/mpfb2/base.obj"), std::string::npos)
      << broken.output;
}
