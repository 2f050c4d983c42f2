// Asset root resolution (see assets.h). LAYERS_SOURCE_ASSET_ROOT is a
// compile definition set by libs/scene/CMakeLists.txt: <source>/assets.
#include "layers/body/assets.h"

#include <cstdlib>
#include <filesystem>
#include <system_error>

#include "layers/core/install_paths.h"

#ifndef LAYERS_SOURCE_ASSET_ROOT
#error "LAYERS_SOURCE_ASSET_ROOT must be defined by the build"
#endif

namespace layers::body {

std::string default_asset_root() {
  const char* env = std::getenv("LAYERS_ASSETS");
  if (env && *env) return env;
  const std::string installed = installed_dir(kInstalledAssetDir);
  if (!installed.empty()) return installed;
  return LAYERS_SOURCE_ASSET_ROOT;
}

std::string resolve_asset_root(const std::string& root) { return root.empty() ? default_asset_root() : root; }

std::string body_asset_dir(const std::string& root) { return resolve_asset_root(root) + "/body/mpfb2"; }

std::string motion_asset_dir(const std::string& root) { return resolve_asset_root(root) + "/motions"; }

std::string asset_relative_name(const std::string& path, const std::string& root) {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path file = fs::weakly_canonical(fs::absolute(path, ec), ec);
  if (ec) return path;
  const fs::path base = fs::weakly_canonical(fs::absolute(motion_asset_dir(root), ec), ec);
  if (ec) return path;
  const fs::path rel = file.lexically_relative(base);
  if (rel.empty() || *rel.begin() == "..") return file.string();
  return rel.generic_string();
}

}  // namespace layers::body
