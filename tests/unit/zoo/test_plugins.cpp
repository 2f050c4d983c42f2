// Plugin loading through dlopen: the good plugin, a wrong API version, the
// ABI handshake, a missing entry point, an unloadable file, a duplicate
// model name, what a plugin exports, and the LAYERS_PLUGIN_PATH search.
#include <gtest/gtest.h>

#include <dlfcn.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "error_of.h"
#include "layers/core/error.h"
#include "layers/zoo/plugin_abi.h"
#include "layers/zoo/plugin_hash.h"
#include "layers/zoo/plugin_loader.h"
#include "temp_dir.h"
#include "test_paths.h"

namespace fs = std::filesystem;
namespace zoo = layers::zoo;
using layers::test::plugin_file;

namespace {

std::string load_error(zoo::Registry& r, const std::string& path) {
  try {
    zoo::load_file(r, path);
  } catch (const layers::InputError& e) {
    return e.what();
  }
  return "(no error)";
}

std::string canonical(const std::string& p) { return fs::canonical(p).string(); }

// Sets LAYERS_PLUGIN_PATH for one test and restores it afterwards.
class PluginPathEnv {
 public:
  explicit PluginPathEnv(const std::string& value) {
    if (const char* old = std::getenv("LAYERS_PLUGIN_PATH")) old_ = old, had_ = true;
    ::setenv("LAYERS_PLUGIN_PATH", value.c_str(), 1);
  }
  ~PluginPathEnv() {
    if (had_)
      ::setenv("LAYERS_PLUGIN_PATH", old_.c_str(), 1);
    else
      ::unsetenv("LAYERS_PLUGIN_PATH");
  }

 private:
  std::string old_;
  bool had_ = false;
};

}  // namespace

TEST(PluginLoader, GoodPluginRegistersItsModel) {
  zoo::Registry r;
  zoo::LoadedPlugin p = zoo::load_file(r, plugin_file("test_constant_velocity"));
  EXPECT_EQ(p.path, canonical(plugin_file("test_constant_velocity")));
  EXPECT_EQ(p.models, std::vector<std::string>{"test_constant_velocity"});
  ASSERT_TRUE(r.contains("test_constant_velocity"));
  EXPECT_EQ(r.find("test_constant_velocity")->plugin_path, p.path);
  EXPECT_EQ(r.find("test_constant_velocity")->description,
            "test model: constant velocity with one learnable damping scalar");
  // Loading it again into the same registry is harmless.
  EXPECT_EQ(zoo::load_file(r, plugin_file("test_constant_velocity")).models, p.models);
  EXPECT_EQ(r.names().size(), 1u);
}

TEST(PluginLoader, WrongApiVersionAsksForRebuild) {
  zoo::Registry r;
  std::string path = canonical(plugin_file("test_wrong_api"));
  EXPECT_EQ(load_error(r, path), path + ": built for zoo API v999, this layers expects v" +
                                     std::to_string(zoo::api_version()) + "; rebuild the plugin against this layers");
  EXPECT_TRUE(r.names().empty());
}

TEST(PluginLoader, AbiHandshakeRefusesAnotherLibTorch) {
  zoo::Registry r;
  std::string path = canonical(plugin_file("test_wrong_abi"));
  const std::string host_torch = zoo::host_plugin_abi().torch_version;
  ASSERT_FALSE(host_torch.empty());
  EXPECT_EQ(load_error(r, path), path + ": built against LibTorch 0.4.1, this layers uses " + host_torch +
                                     "; rebuild the plugin against this layers");
  EXPECT_TRUE(r.names().empty());
}

TEST(PluginAbi, NamesEveryDifference) {
  const zoo::PluginAbi& host = zoo::host_plugin_abi();
  EXPECT_EQ(zoo::plugin_abi_mismatch(host, host), "");
  ASSERT_GE(host.type_count, 10u);
  zoo::PluginAbi plugin = host;
  plugin.cxx11_abi = host.cxx11_abi ? 0 : 1;
  // The Model layout: the fifth crossing type.
  ASSERT_STREQ(plugin.types[4].name, "layers::zoo::Model");
  plugin.types[4].size += 8;
  const std::string m = zoo::plugin_abi_mismatch(host, plugin);
  EXPECT_NE(m.find("built with _GLIBCXX_USE_CXX11_ABI=" + std::to_string(plugin.cxx11_abi) + ", this layers with " +
                   std::to_string(host.cxx11_abi)),
            std::string::npos)
      << m;
  EXPECT_NE(
      m.find("layers::zoo::Model is " + std::to_string(host.types[4].size + 8) + " bytes (align " +
             std::to_string(host.types[4].align) + ") in the plugin, " + std::to_string(host.types[4].size) + " bytes"),
      std::string::npos)
      << m;
  EXPECT_EQ(m.find("LibTorch"), std::string::npos) << m;
  // A plugin with another list of crossing types is named at the first difference.
  zoo::PluginAbi fewer = host;
  fewer.type_count = 3;
  EXPECT_NE(zoo::plugin_abi_mismatch(host, fewer).find("list of crossing types differs from this layers' at entry 4"),
            std::string::npos);
}

TEST(PluginLoader, PluginExportsOnlyItsEntryPoint) {
  void* handle = dlopen(canonical(plugin_file("test_constant_velocity")).c_str(), RTLD_NOW | RTLD_LOCAL);
  ASSERT_NE(handle, nullptr) << dlerror();
  EXPECT_NE(dlsym(handle, "layers_plugin_register"), nullptr);
  // Defined in the plugin with default visibility; hidden by its exports map.
  EXPECT_EQ(dlsym(handle, "layers_test_plugin_private_helper"), nullptr);
  dlclose(handle);
}

TEST(PluginLoader, MissingEntryPointNamesFileAndSymbol) {
  zoo::Registry r;
  std::string path = canonical(plugin_file("test_no_entry"));
  EXPECT_EQ(load_error(r, path), path +
                                     ": not a layers plugin: no entry point 'layers_plugin_register' "
                                     "(define it with LAYERS_PLUGIN from layers/zoo/plugin.h)");
}

TEST(PluginLoader, DataEntryPointIsRefusedByItsSymbolType) {
  zoo::Registry r;
  std::string path = canonical(plugin_file("test_data_entry"));
  EXPECT_EQ(load_error(r, path), path +
                                     ": not a layers plugin: entry point 'layers_plugin_register' expected a "
                                     "function symbol, got a data object");
  EXPECT_TRUE(r.names().empty());
}

TEST(PluginLoader, DirectoriesAndDanglingLinksNamedLikePluginsAreReported) {
  layers::test::TempDir dir("layers-zoo");
  fs::create_directories(dir.file("liblayers_plugin_folder.so"));
  fs::create_symlink(dir.file("nowhere.so"), dir.file("liblayers_plugin_dangling.so"));
  zoo::Registry r;
  zoo::LoadReport report = zoo::load_all(r, {dir.path()});
  ASSERT_EQ(report.problems.size(), 2u);
  EXPECT_EQ(report.problems[0].message,
            dir.file("liblayers_plugin_dangling.so") + ": expected a plugin file, got a dangling symbolic link");
  EXPECT_EQ(report.problems[1].message,
            dir.file("liblayers_plugin_folder.so") + ": expected a plugin file, got a directory");
}

TEST(PluginLoader, UnloadableFileGivesDlerror) {
  layers::test::TempDir dir("layers-zoo");
  std::string path = dir.write("liblayers_plugin_garbage.so", std::string(256, 'x'));
  zoo::Registry r;
  std::string message = load_error(r, path);
  EXPECT_EQ(message.rfind(canonical(path) + ": cannot load plugin: ", 0), 0u) << message;
  EXPECT_NE(message.find("invalid ELF header"), std::string::npos) << message;  // dlerror's words
  EXPECT_EQ(load_error(r, dir.file("liblayers_plugin_missing.so")),
            dir.file("liblayers_plugin_missing.so") + ": no such plugin file");
}

// A plugin cut short (a copy interrupted, a full disk) is refused before
// dlopen, which would map it and die with SIGBUS past its end or load a
// library missing its tail; it shadows nothing.
TEST(PluginLoader, TruncatedPluginIsRefusedAndShadowsNothing) {
  layers::test::TempDir first("layers-zoo-a"), second("layers-zoo-b");
  const std::string name = "liblayers_plugin_test_constant_velocity.so";
  std::ifstream in(plugin_file("test_constant_velocity"), std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  for (int percent : {10, 75, 90, 99}) {
    const std::string cut = first.write(name, bytes.substr(0, bytes.size() * percent / 100));
    zoo::Registry r;
    const std::string message = load_error(r, cut);
    EXPECT_EQ(message.rfind(canonical(cut) + ": cannot load plugin: truncated: its ELF headers need ", 0), 0u)
        << percent << "%: " << message;
    EXPECT_TRUE(r.names().empty());
  }
  fs::copy_file(plugin_file("test_constant_velocity"), second.file(name));
  PluginPathEnv env(first.path() + ":" + second.path());
  zoo::Registry r;
  const zoo::LoadReport report = zoo::load_all(r);
  ASSERT_FALSE(report.loaded.empty());
  EXPECT_EQ(r.find("test_constant_velocity")->plugin_path, canonical(second.file(name)));
  EXPECT_TRUE(report.shadowed.empty());
  ASSERT_FALSE(report.problems.empty());
  EXPECT_NE(report.problems[0].message.find("truncated"), std::string::npos);
}

TEST(PluginLoader, DuplicateNameNamesBothFilesAndRollsBack) {
  zoo::Registry r;
  zoo::load_file(r, plugin_file("test_constant_velocity"));
  std::string good = canonical(plugin_file("test_constant_velocity"));
  std::string dup = canonical(plugin_file("test_duplicate"));
  EXPECT_EQ(load_error(r, dup), dup + ": registration failed: model 'test_constant_velocity': registered twice: by " +
                                    good + " and by " + dup +
                                    "; model names must be unique, remove or rename one of the plugins");
  // The model it registered before failing was removed with it.
  EXPECT_EQ(r.names(), std::vector<std::string>{"test_constant_velocity"});
  EXPECT_EQ(r.find("test_constant_velocity")->plugin_path, good);
}

TEST(PluginLoader, LoadAllReportsEveryProblem) {
  zoo::Registry r;
  zoo::LoadReport report = zoo::load_all(r, {layers::test::plugin_dir(), "/nonexistent/plugins"});
  ASSERT_EQ(report.searched, std::vector<std::string>{canonical(layers::test::plugin_dir())});
  ASSERT_EQ(report.loaded.size(), 1u);
  EXPECT_EQ(report.loaded[0].models, std::vector<std::string>{"test_constant_velocity"});
  // Files load in name order: data_entry, duplicate (after the good one),
  // no_entry, wrong_abi, wrong_api.
  ASSERT_EQ(report.problems.size(), 5u);
  EXPECT_NE(report.problems[0].message.find("expected a function symbol"), std::string::npos);
  EXPECT_EQ(report.problems[1].path, canonical(plugin_file("test_duplicate")));
  EXPECT_NE(report.problems[1].message.find("registered twice"), std::string::npos);
  EXPECT_NE(report.problems[2].message.find("no entry point"), std::string::npos);
  EXPECT_NE(report.problems[3].message.find("built against LibTorch 0.4.1"), std::string::npos);
  EXPECT_NE(report.problems[4].message.find("built for zoo API v999"), std::string::npos);
  EXPECT_EQ(r.names(), std::vector<std::string>{"test_constant_velocity"});
}

TEST(PluginLoader, SearchesLayersPluginPathFirstAndShadows) {
  layers::test::TempDir first("layers-zoo-a"), second("layers-zoo-b");
  const std::string name = "liblayers_plugin_test_constant_velocity.so";
  fs::copy_file(plugin_file("test_constant_velocity"), first.file(name));
  fs::copy_file(plugin_file("test_constant_velocity"), second.file(name));
  PluginPathEnv env(first.path() + "::" + second.path() + ":/nonexistent/layers");

  std::vector<std::string> path = zoo::plugin_search_path();
  ASSERT_GE(path.size(), 2u);
  EXPECT_EQ(path[0], canonical(first.path()));
  EXPECT_EQ(path[1], canonical(second.path()));
  // Then plugins/ next to the test binary and its own folder, when present.
  fs::path exe_dir = fs::read_symlink("/proc/self/exe").parent_path();
  EXPECT_EQ(path.back(), canonical(exe_dir.string()));

  zoo::Registry r;
  zoo::LoadReport report = zoo::load_all(r);
  EXPECT_EQ(report.searched, path);
  ASSERT_FALSE(report.loaded.empty());
  EXPECT_EQ(report.loaded[0].path, canonical(first.file(name)));
  EXPECT_EQ(r.find("test_constant_velocity")->plugin_path, canonical(first.file(name)));
  ASSERT_EQ(report.shadowed.size(), 1u);
  EXPECT_EQ(report.shadowed[0].message,
            canonical(second.file(name)) + ": skipped, shadowed by " + canonical(first.file(name)));
  ASSERT_FALSE(report.problems.empty());
  EXPECT_EQ(report.problems[0].message, "/nonexistent/layers: LAYERS_PLUGIN_PATH entry is not a directory");
}

// Issue 62 C2: a plugin copy with part of its code zeroed loaded, shadowed
// the installed plugin and crashed `eval`. The build records each plugin's
// content hash beside it; a copy whose bytes no longer match is refused
// before dlopen, and a copy with no recorded hash does not shadow one with
// it (it is passed over with a warning).
TEST(PluginLoader, RecordedHashesRefuseChangedCopiesAndUnrecordedOnesDoNotShadow) {
  const std::string built = plugin_file("test_constant_velocity");
  ASSERT_TRUE(fs::exists(zoo::plugin_hash_file(built))) << "the build records a hash beside each plugin";
  {
    zoo::Registry r;
    EXPECT_TRUE(zoo::load_file(r, built).verified);
  }
  layers::test::TempDir first("layers-zoo-damaged"), second("layers-zoo-recorded");
  const std::string name = "liblayers_plugin_test_constant_velocity.so";
  // A copy with its record, then a byte of it changed.
  fs::copy_file(built, first.file(name));
  fs::copy_file(zoo::plugin_hash_file(built), zoo::plugin_hash_file(first.file(name)));
  {
    std::fstream f(first.file(name), std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(static_cast<std::streamoff>(fs::file_size(built) / 2));
    f.put('\x5a');
  }
  zoo::Registry r;
  const std::string said = layers::test::error_of<layers::InputError>([&] { zoo::load_file(r, first.file(name)); });
  EXPECT_NE(said.find(canonical(first.file(name)) + ": content hash: expected " + zoo::plugin_content_hash(built) +
                      " (recorded in "),
            std::string::npos)
      << said;
  EXPECT_TRUE(r.names().empty());
  // The same damaged copy without a record, first on the path, and the
  // recorded original after it: the original loads.
  fs::remove(zoo::plugin_hash_file(first.file(name)));
  fs::copy_file(built, second.file(name));
  zoo::record_plugin_hash(second.file(name));
  PluginPathEnv env(first.path() + ":" + second.path());
  zoo::Registry both;
  const zoo::LoadReport report = zoo::load_all(both, {first.path(), second.path()});
  ASSERT_EQ(report.loaded.size(), 1u);
  EXPECT_EQ(report.loaded[0].path, canonical(second.file(name)));
  EXPECT_TRUE(report.loaded[0].verified);
  ASSERT_EQ(report.passed_over.size(), 1u);
  EXPECT_NE(report.passed_over[0].message.find(canonical(first.file(name)) +
                                               ": skipped although first on the plugin path: it has no recorded "
                                               "content hash and " +
                                               canonical(second.file(name)) + " has one"),
            std::string::npos)
      << report.passed_over[0].message;
  EXPECT_TRUE(report.shadowed.empty());
}

TEST(PluginLoader, EmptyPluginPathFindsNothingThere) {
  layers::test::TempDir empty("layers-zoo-empty");
  PluginPathEnv env(empty.path());
  zoo::Registry r;
  zoo::LoadReport report = zoo::load_all(r);
  EXPECT_EQ(report.searched.front(), canonical(empty.path()));
  for (const auto& p : report.loaded) EXPECT_NE(p.path.rfind(canonical(empty.path()), 0), 0u);
}
