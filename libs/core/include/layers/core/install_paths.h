// layers/core/install_paths.h -- where the running program lies, and the
// folders an installed toolkit keeps beside it. One prefix layout, shared
// by the plugin search (zoo) and the asset lookup (scene):
//   <prefix>/bin/layers                  the program
//   <prefix>/lib/layers/plugins/         model plugins
//   <prefix>/share/layers/{assets,configs}
#pragma once

#include <string>

namespace layers {

// Folder of the running executable (/proc/self/exe), or "" when unknown.
std::string executable_dir();

// <executable_dir>/../<relative>, lexically normalised, when that folder
// exists; "" otherwise (also when the executable's folder is unknown).
std::string installed_dir(const std::string& relative);

// The relative folders of the layout above.
inline constexpr const char* kInstalledPluginDir = "lib/layers/plugins";
inline constexpr const char* kInstalledAssetDir = "share/layers/assets";
inline constexpr const char* kInstalledConfigDir = "share/layers/configs";

}  // namespace layers
