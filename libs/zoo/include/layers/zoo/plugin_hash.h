// layers/zoo/plugin_hash.h -- a plugin's content hash, recorded beside it
// (<plugin>.hash: the 16 hex digits of core/checksum.h's hash of the file's
// bytes) when the build links it and when it is installed, and checked by
// the loader before dlopen: a plugin whose bytes changed since (a damaged
// or edited copy) is refused instead of loaded. Torch-free.
#pragma once

#include <string>

namespace layers::zoo {

// "<plugin>.hash".
std::string plugin_hash_file(const std::string& plugin);

// The hash of the file's bytes (InputError when it cannot be read).
std::string plugin_content_hash(const std::string& plugin);

// Writes <plugin>.hash (atomically) with plugin_content_hash(plugin).
void record_plugin_hash(const std::string& plugin);

enum class PluginHash { Verified, Unrecorded };
// Verified when <plugin>.hash exists and matches the file; Unrecorded when
// there is none; InputError naming the plugin when it differs or the
// record is not one.
PluginHash check_plugin_hash(const std::string& plugin);

}  // namespace layers::zoo
