// layers/zoo/plugin.h -- what a model plugin includes to register itself.
//
// A plugin is a shared library named liblayers_plugin_<name>.so (build it
// with layers_plugin() in CMake) containing exactly one
//
//   LAYERS_PLUGIN(registry) {
//     registry.add("my_model", "one-line description",
//                  [](const layers::cfg::Node& params) { return std::make_shared<MyModel>(params); });
//   }
//
// The macro defines the extern "C" entry point layers_plugin_register with
// the plugin's own LAYERS_ZOO_API_VERSION compiled in. When the host's
// version differs, the plugin registers nothing and returns its version,
// and the loader asks for a rebuild. Exceptions thrown by the block are
// caught inside the plugin (none crosses the C boundary) and reported to
// the loader through the registry; whatever the plugin registered before
// the failure is then removed. This header needs no torch; include
// layers/zoo/model.h for the Model interface.
#pragma once

#include <exception>
#include <type_traits>

#include "layers/zoo/api_version.h"
#include "layers/zoo/registry.h"

namespace layers::zoo {

// The entry point's type and name, as the loader looks them up.
using PluginEntry = int (*)(Registry* registry, int host_api_version);
inline constexpr const char* kPluginEntryPoint = "layers_plugin_register";

// Return codes of the entry point: 0 registered; kPluginFailed: the block
// threw (message given to Registry::report_plugin_error); any positive
// value: the plugin's API version, which differs from the host's.
inline constexpr int kPluginFailed = -1;

namespace plugin_detail {

// Compiled into each plugin (internal linkage), so the version checked here
// is the plugin's own.
static inline int run_registration(Registry* registry, int host_api_version,
                                   void (*body)(Registry&)) noexcept {
  if (host_api_version != LAYERS_ZOO_API_VERSION) return LAYERS_ZOO_API_VERSION;
  const char* failure = nullptr;
  try {
    body(*registry);
    return 0;
  } catch (const std::exception& e) {
    try {
      registry->report_plugin_error(e.what());
    } catch (...) {
      failure = "registration failed and its message could not be reported";
    }
  } catch (...) {
    failure = "registration threw an exception not derived from std::exception";
  }
  if (failure) {
    try {
      registry->report_plugin_error(failure);
    } catch (...) {
    }
  }
  return kPluginFailed;
}

}  // namespace plugin_detail
}  // namespace layers::zoo

#define LAYERS_PLUGIN(registry)                                                                   \
  static void layers_plugin_body(::layers::zoo::Registry& registry);                              \
  extern "C" __attribute__((visibility("default"))) int layers_plugin_register(                   \
      ::layers::zoo::Registry* layers_registry, int layers_host_api_version);                     \
  static_assert(std::is_same_v<decltype(&layers_plugin_register), ::layers::zoo::PluginEntry>);   \
  extern "C" int layers_plugin_register(::layers::zoo::Registry* layers_registry,                 \
                                        int layers_host_api_version) {                            \
    return ::layers::zoo::plugin_detail::run_registration(layers_registry,                        \
                                                          layers_host_api_version,                \
                                                          &layers_plugin_body);                   \
  }                                                                                               \
  static void layers_plugin_body(::layers::zoo::Registry& registry)
