// layers/scene/assets.h -- where the shared assets (MPFB2 body, CMU BVH)
// are read from at run time. They are never copied into the project.
#pragma once

#include <string>

namespace layers::scene {

// The asset root: $LAYERS_ASSETS when set and non-empty, otherwise
// <project source root>/../shared/assets as baked in at build time.
std::string default_asset_root();

// `root` when non-empty, else default_asset_root().
std::string resolve_asset_root(const std::string& root);

// Paths inside an asset root.
std::string body_asset_dir(const std::string& root);    // <root>/body/mpfb2
std::string motion_asset_dir(const std::string& root);  // <root>/motions/cmu

}  // namespace layers::scene
