// layers/zoo/plugin_loader.h -- finding and loading model plugins.
//
// A plugin is a file named liblayers_plugin_<name>.so exporting the entry
// point that LAYERS_PLUGIN defines (plugin.h). Before dlopen, a plugin
// with a recorded content hash (<file>.hash, plugin_hash.h: written by the
// build and the install) must match it, or it is refused. Search order,
// first match of a file name wins (a later file with the same name is
// skipped as shadowed, so LAYERS_PLUGIN_PATH can override an installed
// plugin), except that a file without a recorded hash never shadows one
// with it (a hand-copied or damaged copy cannot hide the checked one):
//   1. every directory of LAYERS_PLUGIN_PATH (colon-separated), in order;
//   2. plugins/ next to the running binary (/proc/self/exe);
//   3. the directory of the running binary itself;
//   4. lib/layers/plugins of an installed prefix (<binary>/../lib/layers/plugins).
// Within a directory files load in name order. Loaded plugins stay loaded
// for the life of the process (their factories and models live in them).
// Before its entry point is called, the entry symbol must be an ELF
// function; an entry named like a plugin that is a directory, a dangling
// link or not loadable is reported as a problem (an error under
// `layers models --strict`). Loading is in-process: a plugin's own static
// constructors run inside dlopen, so one that aborts or crashes takes the
// process with it -- no check can run before them.
// Torch-free.
#pragma once

#include <string>
#include <vector>

#include "layers/zoo/registry.h"

namespace layers::zoo {

// The zoo API version this build of layers expects from plugins.
int api_version();

struct LoadedPlugin {
  std::string path;                 // canonical path of the library
  std::vector<std::string> models;  // names it registered
  bool verified = false;            // its bytes matched its recorded hash (false: none recorded)
};

struct PluginProblem {
  std::string path;     // the plugin file or search directory concerned
  std::string message;  // complete, starts with the path
};

struct LoadReport {
  std::vector<std::string> searched;  // directories, in search order
  std::vector<LoadedPlugin> loaded;
  std::vector<PluginProblem> problems;  // plugins refused (print as warnings)
  std::vector<PluginProblem> shadowed;  // skipped: same file name found earlier
  // Skipped although found earlier: no recorded hash, and a later file of
  // the same name has one (print as warnings).
  std::vector<PluginProblem> passed_over;
};

// The directories of the search order above that exist, canonical and
// without repeats.
std::vector<std::string> plugin_search_path();

// Loads one plugin file into `registry`. Throws layers::InputError naming
// the file when it cannot be opened (with dlerror's text), has no entry
// point, was built for another API version, fails to register or registers
// no model. A failed plugin leaves nothing in the registry. Loading a file
// that this registry already loaded returns its models again.
LoadedPlugin load_file(Registry& registry, const std::string& path);

// Loads every liblayers_plugin_*.so in `directories` (in order, see the
// shadowing rule above), collecting failures instead of throwing.
LoadReport load_all(Registry& registry, const std::vector<std::string>& directories);
// The same over plugin_search_path(); a LAYERS_PLUGIN_PATH entry that is
// not a directory is reported as a problem.
LoadReport load_all(Registry& registry);

}  // namespace layers::zoo
