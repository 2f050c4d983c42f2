// A plugin's recorded content hash (see plugin_hash.h).
#include "layers/zoo/plugin_hash.h"

#include <filesystem>
#include <fstream>
#include <vector>

#include "layers/core/atomic_file.h"
#include "layers/core/checksum.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"

namespace layers::zoo {

std::string plugin_hash_file(const std::string& plugin) { return plugin + ".hash"; }

std::string plugin_content_hash(const std::string& plugin) {
  std::ifstream in(plugin, std::ios::binary);
  if (!in) throw InputError(plugin, "", "a readable plugin file", "it cannot be opened");
  ContentHash hash;
  std::vector<char> block(1 << 16);
  while (in) {
    in.read(block.data(), static_cast<std::streamsize>(block.size()));
    hash.add(block.data(), static_cast<std::size_t>(in.gcount()));
  }
  return hash.hex();
}

void record_plugin_hash(const std::string& plugin) {
  write_text_atomic(plugin_hash_file(plugin), plugin_content_hash(plugin) + "\n");
}

PluginHash check_plugin_hash(const std::string& plugin) {
  const std::string record = plugin_hash_file(plugin);
  std::error_code ec;
  if (!std::filesystem::exists(record, ec)) return PluginHash::Unrecorded;
  std::string recorded = read_text_file(record);
  while (!recorded.empty() && (recorded.back() == '\n' || recorded.back() == '\r')) recorded.pop_back();
  if (recorded.size() != 16 || recorded.find_first_not_of("0123456789abcdef") != std::string::npos)
    throw InputError(record, "", "16 hex digits (the plugin's content hash, written by its build or install)",
                     "'" + recorded.substr(0, 40) + "'");
  const std::string actual = plugin_content_hash(plugin);
  if (actual != recorded)
    throw InputError(plugin, "content hash",
                     recorded + " (recorded in " + record +
                         " when it was built or installed; the file changed since: rebuild or reinstall it)",
                     actual);
  return PluginHash::Verified;
}

}  // namespace layers::zoo
