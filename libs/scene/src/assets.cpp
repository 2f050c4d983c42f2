// Asset root resolution (see assets.h). LAYERS_DEFAULT_ASSET_ROOT is a
// compile definition set by libs/scene/CMakeLists.txt.
#include "layers/scene/assets.h"

#include <cstdlib>

#ifndef LAYERS_DEFAULT_ASSET_ROOT
#error "LAYERS_DEFAULT_ASSET_ROOT must be defined by the build"
#endif

namespace layers::scene {

std::string default_asset_root() {
  const char* env = std::getenv("LAYERS_ASSETS");
  if (env && *env) return env;
  return LAYERS_DEFAULT_ASSET_ROOT;
}

std::string resolve_asset_root(const std::string& root) { return root.empty() ? default_asset_root() : root; }

std::string body_asset_dir(const std::string& root) { return resolve_asset_root(root) + "/body/mpfb2"; }

std::string motion_asset_dir(const std::string& root) { return resolve_asset_root(root) + "/motions/cmu"; }

}  // namespace layers::scene
