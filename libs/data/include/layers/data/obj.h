// layers/data/obj.h -- Wavefront OBJ triangle meshes (import and export).
//
// read_obj reads with layers::geometry's OBJ reader (geometry/obj.h: v, vt
// and f lines, v/vt/vn face vertices, negative indices; errors name the
// file and line) and fan-triangulates polygons.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace layers::data {

struct ObjMesh {
  std::vector<float> positions;        // [V,3]
  std::vector<std::int32_t> faces;     // [F,3]
  std::vector<float> uv;               // [U,2]; may be empty
  std::vector<std::int32_t> uv_faces;  // [F,3] into uv; empty when no face has vt
  std::int64_t n_vertices() const { return static_cast<std::int64_t>(positions.size() / 3); }
  std::int64_t n_faces() const { return static_cast<std::int64_t>(faces.size() / 3); }
};

// Writes atomically. Floats are written with 9 significant digits, so a
// read back is bit-identical. Throws InputError on inconsistent sizes or
// out-of-range indices.
void write_obj(const std::string& path, const ObjMesh& mesh);
void write_obj(const std::string& path, const std::vector<float>& positions, const std::vector<std::int32_t>& faces,
               const std::vector<float>& uv = {}, const std::vector<std::int32_t>& uv_faces = {});
ObjMesh read_obj(const std::string& path);

}  // namespace layers::data
