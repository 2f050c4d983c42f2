// Wavefront OBJ reading and writing (see obj.h).
#include "layers/data/obj.h"

#include <cstdio>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/geometry/obj.h"
#include "sequence_rules.h"

namespace layers::data {
namespace {

void check_mesh(const std::string& path, const ObjMesh& mesh) {
  if (mesh.positions.size() % 3 != 0) {
    throw InputError(path, "positions", "a multiple of 3 floats ([V,3])", std::to_string(mesh.positions.size()));
  }
  if (mesh.faces.size() % 3 != 0)
    throw InputError(path, "faces", "a multiple of 3 indices ([F,3])", std::to_string(mesh.faces.size()));
  if (mesh.uv.size() % 2 != 0)
    throw InputError(path, "uv", "a multiple of 2 floats ([U,2])", std::to_string(mesh.uv.size()));
  if (!mesh.uv_faces.empty() && mesh.uv_faces.size() != mesh.faces.size()) {
    throw InputError(path, "uv_faces", std::to_string(mesh.faces.size()) + " indices (one per face corner)",
                     std::to_string(mesh.uv_faces.size()));
  }
  if (auto problem = check_index_range(mesh.faces, 0, mesh.n_vertices(), 3))
    throw InputError::message(path, "faces", *problem);
  if (auto problem = check_index_range(mesh.uv_faces, 0, static_cast<std::int64_t>(mesh.uv.size() / 2), 3)) {
    throw InputError::message(path, "uv_faces", *problem);
  }
}

std::string format_float(float v) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.9g", static_cast<double>(v));
  return buffer;
}

}  // namespace

void write_obj(const std::string& path, const ObjMesh& mesh) {
  check_mesh(path, mesh);
  std::string text = "# layers OBJ export\n";
  text.reserve(mesh.positions.size() * 14 + mesh.faces.size() * 12);
  for (std::size_t i = 0; i + 2 < mesh.positions.size(); i += 3) {
    text += "v " + format_float(mesh.positions[i]) + " " + format_float(mesh.positions[i + 1]) + " " +
            format_float(mesh.positions[i + 2]) + "\n";
  }
  for (std::size_t i = 0; i + 1 < mesh.uv.size(); i += 2) {
    text += "vt " + format_float(mesh.uv[i]) + " " + format_float(mesh.uv[i + 1]) + "\n";
  }
  const bool with_uv = !mesh.uv_faces.empty();
  for (std::size_t f = 0; f < mesh.faces.size(); f += 3) {
    text += "f";
    for (std::size_t c = 0; c < 3; ++c) {
      text += " " + std::to_string(mesh.faces[f + c] + 1);
      if (with_uv) text += "/" + std::to_string(mesh.uv_faces[f + c] + 1);
    }
    text += "\n";
  }
  write_text_atomic(path, text);
}

void write_obj(const std::string& path, const std::vector<float>& positions, const std::vector<std::int32_t>& faces,
               const std::vector<float>& uv, const std::vector<std::int32_t>& uv_faces) {
  write_obj(path, ObjMesh{positions, faces, uv, uv_faces});
}

ObjMesh read_obj(const std::string& path) {
  const geometry::ObjPolygons obj = geometry::read_obj_polygons(path);
  ObjMesh mesh;
  mesh.positions.assign(obj.positions.begin(), obj.positions.end());
  mesh.uv.assign(obj.uv.begin(), obj.uv.end());
  const bool with_uv = !obj.uv_indices.empty();
  for (int f = 0; f < obj.num_faces(); ++f) {  // polygons fan-triangulated
    const int first = obj.face_start[f];
    for (int i = first + 1; i + 1 < obj.face_start[f + 1]; ++i) {
      for (const int c : {first, i, i + 1}) {
        mesh.faces.push_back(obj.indices[c]);
        if (with_uv) mesh.uv_faces.push_back(obj.uv_indices[c]);
      }
    }
  }
  return mesh;
}

}  // namespace layers::data
