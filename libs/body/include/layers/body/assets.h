// layers/body/assets.h -- where the assets (MPFB2 body, CMU BVH clips)
// are read from at run time. They ship in the repository's assets/ folder
// and are installed to <prefix>/share/layers/assets.
#pragma once

#include <string>

namespace layers::body {

// The asset root, the first of: $LAYERS_ASSETS when set and non-empty;
// <executable>/../share/layers/assets when it exists (an installed
// toolkit); <source tree>/assets as baked in at build time.
std::string default_asset_root();

// `root` when non-empty, else default_asset_root().
std::string resolve_asset_root(const std::string& root);

// Paths inside an asset root.
std::string body_asset_dir(const std::string& root);    // <root>/body/mpfb2
std::string motion_asset_dir(const std::string& root);  // <root>/motions (clips in cmu/)

// The name under which a motion file is recorded: its path relative to
// motion_asset_dir(root) when it lies inside (e.g. "cmu/131_01.bvh"), so a
// dataset does not record where it was made; otherwise its absolute path.
std::string asset_relative_name(const std::string& path, const std::string& root);

}  // namespace layers::body
