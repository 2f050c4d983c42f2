// tests/support/test_paths.h -- where the tests find what the build made:
// the `layers` binary, the test plugins (tests/plugins) and the source tree.
// CMake compiles the paths in; an environment variable of the same name
// overrides each (to test an installed build).
#pragma once

#include <cstdlib>
#include <string>

namespace layers::test {

namespace detail {
inline std::string path_setting(const char* env, const char* built_in) {
  const char* value = std::getenv(env);
  return (value && *value) ? value : built_in;
}
}  // namespace detail

inline std::string layers_bin() { return detail::path_setting("LAYERS_BIN", LAYERS_TEST_BIN); }
inline std::string plugin_dir() { return detail::path_setting("LAYERS_TEST_PLUGIN_DIR", LAYERS_TEST_PLUGIN_DIR); }
inline std::string source_dir() { return detail::path_setting("LAYERS_SOURCE_DIR", LAYERS_TEST_SOURCE_DIR); }

// Path of liblayers_plugin_<name>.so in the test plugin folder.
inline std::string plugin_file(const std::string& name) { return plugin_dir() + "/liblayers_plugin_" + name + ".so"; }

}  // namespace layers::test
