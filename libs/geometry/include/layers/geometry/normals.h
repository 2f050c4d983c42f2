// layers/geometry/normals.h -- face areas, face normals and area-weighted
// vertex normals. Faces are assumed consistently wound (counter-clockwise
// seen from the side the normal points to). Faces must be valid for the
// vertices (see validate()); this is not re-checked here.
#pragma once

#include <Eigen/Core>

#include "layers/geometry/mesh.h"

namespace layers::geometry {

// Unit normal per face; a degenerate (zero-area) face gets (0, 0, 0).
Points face_normals(const Points& vertices, const Faces& faces);

// Area per face.
Eigen::VectorXf face_areas(const Points& vertices, const Faces& faces);

// Unit normal per vertex: the area-weighted sum of the normals of its faces,
// normalised. A vertex used by no face (or only by degenerate faces) gets
// (0, 0, 0).
Points vertex_normals(const Points& vertices, const Faces& faces);
inline Points vertex_normals(const TriMesh& mesh) { return vertex_normals(mesh.vertices, mesh.faces); }

}  // namespace layers::geometry
