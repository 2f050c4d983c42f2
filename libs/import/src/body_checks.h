// body_checks.h -- what every imported body must be (import's own): a
// height that reads as metres, with each failure one line naming the file.
#pragma once

#include <string>

#include "layers/geometry/mesh.h"

namespace layers::import {

// InputError unless the mesh's y extent is within kMin/kMaxBodyHeight
// (body_import.h) and every position is finite.
void check_body_height(const geometry::TriMesh& mesh, const std::string& file);

}  // namespace layers::import
