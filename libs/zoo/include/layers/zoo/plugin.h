// layers/zoo/plugin.h -- what a model plugin includes to register itself.
//
// A plugin is a shared library named liblayers_plugin_<name>.so (build it
// with layers_plugin() in CMake, which exports only the entry point)
// containing exactly one LAYERS_PLUGIN block. Every plugin of this tree
// declares its model's registry entry (a zoo::ModelSpec: name, one-line
// description, factory; registry.h) in the torch-free header src/spec.h
// and registers it in src/register.cpp:
//
//   // spec.h
//   std::shared_ptr<zoo::Model> make_my_model(const cfg::Node& params);
//   inline constexpr zoo::ModelSpec kMyModel{"my_model", "one-line description", make_my_model};
//
//   // register.cpp
//   LAYERS_PLUGIN(registry) { registry.add(kMyModel); }
//
// The macro defines the extern "C" entry point layers_plugin_register
// (plugin_abi.h). It first writes the plugin's ABI record (zoo API version,
// LibTorch version, string ABI, layouts of the crossing types; see
// plugin_abi_of.h) and compares it with the host's: when they differ the
// plugin registers nothing and the loader names the differences.
// Exceptions thrown by the block are caught inside the plugin (none crosses
// the C boundary) and reported to the loader through the registry;
// whatever the plugin registered before the failure is then removed.
#pragma once

#include <cstring>
#include <exception>
#include <type_traits>

#include "layers/zoo/plugin_abi.h"
#include "layers/zoo/plugin_abi_of.h"
#include "layers/zoo/registry.h"

namespace layers::zoo {
namespace plugin_detail {

// Compiled into each plugin (internal linkage), so the record written and
// compared here is the plugin's own.
static inline int run_registration(const PluginAbi* host, PluginAbi* plugin, Registry* registry,
                                   void (*body)(Registry&)) noexcept {
  if (host->record_size != sizeof(PluginAbi)) return kPluginRecordMismatch;
  fill_plugin_abi(*plugin);
  if (std::memcmp(host, plugin, sizeof(PluginAbi)) != 0) return kPluginAbiMismatch;
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

#define LAYERS_PLUGIN(registry)                                                                                \
  static void layers_plugin_body(::layers::zoo::Registry& registry);                                           \
  extern "C" __attribute__((visibility("default"))) int layers_plugin_register(                                \
      const ::layers::zoo::PluginAbi* layers_host_abi, ::layers::zoo::PluginAbi* layers_plugin_abi,            \
      ::layers::zoo::Registry* layers_registry);                                                               \
  static_assert(std::is_same_v<decltype(&layers_plugin_register), ::layers::zoo::PluginEntry>);                \
  extern "C" int layers_plugin_register(const ::layers::zoo::PluginAbi* layers_host_abi,                       \
                                        ::layers::zoo::PluginAbi* layers_plugin_abi,                           \
                                        ::layers::zoo::Registry* layers_registry) {                            \
    return ::layers::zoo::plugin_detail::run_registration(layers_host_abi, layers_plugin_abi, layers_registry, \
                                                          &layers_plugin_body);                                \
  }                                                                                                            \
  static void layers_plugin_body(::layers::zoo::Registry& registry)
