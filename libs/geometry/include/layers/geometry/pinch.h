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
// Garment-body crossings are reported inside and outside these zones
// (sim/measures.h), and the simulator's collision pass lets the body yield
// to cloth there (docs/sim.md "Contact"): both ask pinch_zones_under().
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

// The pinch zones where cloth lies: pinch_faces() examined on the body
// vertices under the cloth, those within 2 x `distance` + half the cloth's
// longest edge of a cloth vertex (every point of a cloth face lies within
// about half its longest edge of one of its vertices). `cloth` holds the
// cloth's vertices (all garments stacked).
struct PinchZones {
  std::vector<char> covered;  // per body vertex: under the cloth
  std::vector<char> faces;    // per body face: in a pinch zone
};
PinchZones pinch_zones_under(const TriMesh& body, const std::vector<char>& crossing, double distance,
                             const Points& cloth, double longest_edge);
// The same under cloth meshes (the garments of a frame): their vertices,
// and the longest edge of their faces as they stand.
PinchZones pinch_zones_under(const TriMesh& body, const std::vector<char>& crossing, double distance,
                             const std::vector<TriMesh>& cloth);

}  // namespace layers::geometry
