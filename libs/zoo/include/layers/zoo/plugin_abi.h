// layers/zoo/plugin_abi.h -- the handshake at the plugin seam: the entry
// point's C signature and the ABI record both sides compare before any C++
// object crosses.
//
// Model plugins exchange C++ objects with the host (a Registry holding
// std::map and std::function, cfg::Node trees, torch::nn::Module
// subclasses, at::Tensor). That is only safe when both were compiled with
// the same zoo API, the same LibTorch, the same libstdc++ string ABI and
// the same layouts of those types. Each side fills a PluginAbi (a plain C
// record) with what it was compiled against; the plugin compares the
// host's record with its own and registers nothing when they differ, and
// the loader names every difference. Torch-free (the record is filled by
// plugin_abi_of.h, which needs torch).
#pragma once

#include <cstdint>
#include <string>

namespace layers::zoo {

class Registry;

// The layout of one type that crosses the seam.
struct PluginAbiType {
  char name[40];
  std::uint32_t size;
  std::uint32_t align;
};

inline constexpr int kPluginAbiTypes = 16;

// What one side was compiled against. Plain data, zero-filled before it is
// written, so that two records compare with memcmp.
struct PluginAbi {
  std::uint32_t record_size;  // sizeof(PluginAbi) on the writing side: read first
  std::uint32_t api_version;  // LAYERS_ZOO_API_VERSION
  std::uint32_t cxx11_abi;    // _GLIBCXX_USE_CXX11_ABI
  std::uint32_t pointer_size;
  char torch_version[24];  // TORCH_VERSION, e.g. "1.13.0"
  std::uint32_t type_count;
  PluginAbiType types[kPluginAbiTypes];
};

// The entry point's type and name, as the loader looks them up: the host
// passes its record, the plugin writes its own into `plugin` and, when they
// match, registers its models into `registry`.
using PluginEntry = int (*)(const PluginAbi* host, PluginAbi* plugin, Registry* registry);
inline constexpr const char* kPluginEntryPoint = "layers_plugin_register";

// Return codes of the entry point: 0 registered; kPluginFailed: the block
// threw (message given to Registry::report_plugin_error); kPluginAbiMismatch:
// the records differ, nothing registered (the loader describes why);
// kPluginRecordMismatch: the host's record has another size, so the plugin
// could not even write its own.
inline constexpr int kPluginFailed = -1;
inline constexpr int kPluginAbiMismatch = -2;
inline constexpr int kPluginRecordMismatch = -3;

// The host's record (this build of layers), filled once.
const PluginAbi& host_plugin_abi();

// Every difference between the host's and a plugin's record, as one line
// ("built against LibTorch 0.4.1, this layers uses 1.13.0; ..."), ending
// with what to do; empty when they match.
std::string plugin_abi_mismatch(const PluginAbi& host, const PluginAbi& plugin);

}  // namespace layers::zoo
