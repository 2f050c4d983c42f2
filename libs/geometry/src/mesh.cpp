// Mesh validation and concatenation (see mesh.h).
#include "layers/geometry/mesh.h"

#include "layers/core/error.h"

namespace layers::geometry {

void validate(const Faces& faces, int num_vertices, const std::string& what) {
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    for (int c = 0; c < 3; ++c) {
      int v = faces(f, c);
      if (v < 0 || v >= num_vertices) {
        throw InputError(what, "faces[" + std::to_string(f) + "][" + std::to_string(c) + "]",
                         "a vertex index in [0, " + std::to_string(num_vertices) + ")", std::to_string(v));
      }
    }
    if (faces(f, 0) == faces(f, 1) || faces(f, 1) == faces(f, 2) || faces(f, 0) == faces(f, 2)) {
      throw InputError(
          what, "faces[" + std::to_string(f) + "]", "three distinct vertices",
          std::to_string(faces(f, 0)) + ", " + std::to_string(faces(f, 1)) + ", " + std::to_string(faces(f, 2)));
    }
  }
}

TriMesh concatenate(const std::vector<TriMesh>& meshes) {
  Eigen::Index nv = 0, nf = 0;
  for (const auto& m : meshes) {
    nv += m.vertices.rows();
    nf += m.faces.rows();
  }
  TriMesh out;
  out.vertices.resize(nv, 3);
  out.faces.resize(nf, 3);
  Eigen::Index v0 = 0, f0 = 0;
  for (const auto& m : meshes) {
    out.vertices.middleRows(v0, m.vertices.rows()) = m.vertices;
    out.faces.middleRows(f0, m.faces.rows()) = m.faces.array() + static_cast<int>(v0);
    v0 += m.vertices.rows();
    f0 += m.faces.rows();
  }
  return out;
}

}  // namespace layers::geometry
