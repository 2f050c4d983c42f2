// The host's ABI record: what this build of libs/zoo was compiled against
// (filled by the same code every plugin runs, plugin_abi_of.h).
#include "layers/zoo/plugin_abi_of.h"

namespace layers::zoo {

const PluginAbi& host_plugin_abi() {
  static const PluginAbi abi = [] {
    PluginAbi a;
    plugin_detail::fill_plugin_abi(a);
    return a;
  }();
  return abi;
}

}  // namespace layers::zoo
