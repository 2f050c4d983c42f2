// layers/geometry/pinch.h -- where a posed body pinches (docs/metrics.md
// "Pinch zones"): the body faces where no cloth can lie between two parts
// of the body. A face is in a pinch zone when
//  - it crosses another body face, or shares a vertex with one that does
//    (an arm sunk into the torso), or
//  - one of its vertices is closer than `distance` to a body vertex that
//    is more than kPinchDetour x `distance` away along the mesh's edges
//    (two parts of the body, such as the inner arm and the torso or the
//    two thighs, closer than the cloth stack between them needs; on one
//    smooth part of the surface the path along the edges is at most about
//    1.4 times the straight distance).
// Garment-body crossings are reported inside and outside these zones.
#pragma once

#include <vector>

#include "layers/geometry/intersect.h"
#include "layers/geometry/mesh.h"

namespace layers::geometry {

constexpr double kPinchDetour = 2.0;

// One flag per body face. `crossing` marks the faces that cross another
// face of the body (self_crossings(tree).a_faces; empty: none cross).
// distance <= 0 leaves out the proximity part; `examine` (one flag per
// body vertex; null: all) limits it to some vertices, e.g. those under
// the garments (the toes and the lips pinch too, but no cloth goes there).
std::vector<char> pinch_faces(const TriMesh& body, const std::vector<char>& crossing, double distance,
                              const std::vector<char>* examine = nullptr);

}  // namespace layers::geometry
