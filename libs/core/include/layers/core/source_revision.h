// layers/core/source_revision.h -- the source revision this build was made
// from, for records that must say which code produced them (a dataset's
// manifest, `layers --version`). Written at build time by
// cmake/source_revision.cmake.
#pragma once

namespace layers {

// `git describe --always --dirty --abbrev=12` of the source tree at build
// time (e.g. "27a7c27d1f3e" or "27a7c27d1f3e-dirty" when it had uncommitted
// changes), or "unknown" when it was built outside a git checkout.
const char* source_revision();

}  // namespace layers
