// Describes the differences between the host's and a plugin's ABI record
// (plugin_abi.h). Torch-free.
#include <algorithm>
#include <cstring>
#include <string>
#include <vector>

#include "layers/zoo/plugin_abi.h"

namespace layers::zoo {
namespace {

// A fixed-size, possibly unterminated field as a string.
template <std::size_t N>
std::string text(const char (&field)[N]) {
  return std::string(field, strnlen(field, N));
}

std::string layout(const PluginAbiType& t) {
  return std::to_string(t.size) + " bytes (align " + std::to_string(t.align) + ")";
}

}  // namespace

std::string plugin_abi_mismatch(const PluginAbi& host, const PluginAbi& plugin) {
  std::vector<std::string> diffs;
  if (plugin.api_version != host.api_version) {
    diffs.push_back("built for zoo API v" + std::to_string(plugin.api_version) + ", this layers expects v" +
                    std::to_string(host.api_version));
  }
  if (text(plugin.torch_version) != text(host.torch_version)) {
    diffs.push_back("built against LibTorch " + text(plugin.torch_version) + ", this layers uses " +
                    text(host.torch_version));
  }
  if (plugin.cxx11_abi != host.cxx11_abi) {
    diffs.push_back("built with _GLIBCXX_USE_CXX11_ABI=" + std::to_string(plugin.cxx11_abi) + ", this layers with " +
                    std::to_string(host.cxx11_abi));
  }
  if (plugin.pointer_size != host.pointer_size) {
    diffs.push_back("built with " + std::to_string(plugin.pointer_size * 8) + "-bit pointers, this layers with " +
                    std::to_string(host.pointer_size * 8));
  }
  const std::uint32_t n = std::min<std::uint32_t>(std::max(host.type_count, plugin.type_count), kPluginAbiTypes);
  for (std::uint32_t i = 0; i < n; ++i) {
    const PluginAbiType& h = host.types[i];
    const PluginAbiType& p = plugin.types[i];
    if (i >= plugin.type_count || i >= host.type_count || text(h.name) != text(p.name)) {
      diffs.push_back("its list of crossing types differs from this layers' at entry " + std::to_string(i + 1) + " (" +
                      (i < plugin.type_count ? text(p.name) : std::string("none")) + " vs " +
                      (i < host.type_count ? text(h.name) : std::string("none")) + ")");
      break;
    }
    if (h.size != p.size || h.align != p.align) {
      diffs.push_back(text(p.name) + " is " + layout(p) + " in the plugin, " + layout(h) + " here");
    }
  }
  if (diffs.empty()) return "";
  std::string out;
  for (const auto& d : diffs) out += (out.empty() ? "" : "; ") + d;
  return out + "; rebuild the plugin against this layers";
}

}  // namespace layers::zoo
