// layers/import/mesh_checks.h -- what a user's garment mesh must be before
// it is simulated as cloth, each failure one line naming the file: finite
// positions; a size that reads as metres (largest extent 0.05-3 m, so a
// file in centimetres or millimetres is caught); no degenerate face (a
// repeated corner or an area under geometry::kMinClothFaceArea, 1e-8 m^2,
// the simulator's bound); no non-manifold edge (one
// shared by more than two faces); faces wound one way (the two faces of
// an edge run it in opposite directions) and outwards (area-weighted
// normals pointing away from the vertical axis through the centroid on
// the whole: the format's winding, which every contact and collision test
// relies on). Open boundaries (hems, cuffs, a neck opening) are allowed. Where it sits against the body and the other
// layer is checked with the scene (generate/imported_garment.h).
#pragma once

#include <string>

#include "layers/geometry/mesh.h"

namespace layers::import {

inline constexpr double kMinExtent = 0.05, kMaxExtent = 3.0;  // metres

// Throws InputError(file, field, expected, got) on the first failure.
void check_cloth_mesh(const geometry::TriMesh& mesh, const std::string& file);

}  // namespace layers::import
