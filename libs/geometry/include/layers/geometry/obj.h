// layers/geometry/obj.h -- the one Wavefront OBJ reader: vertex positions,
// texture coordinates and polygon faces as written (no triangulation).
//
// Understands v, vt and f lines (vn, o, g, s, usemtl, mtllib, l and
// comments are skipped), face vertices written v, v/vt, v//vn or v/vt/vn,
// and negative (relative) indices. Texture coordinates must be on every
// face or on none. Errors are InputErrors naming the file and line.
#pragma once

#include <string>
#include <vector>

namespace layers::geometry {

struct ObjPolygons {
  std::vector<double> positions;  // [V,3] as written
  std::vector<double> uv;         // [U,2]; may be empty
  std::vector<int> face_start;    // face f uses corners [face_start[f], face_start[f+1])
  std::vector<int> indices;       // 0-based vertex index per corner
  std::vector<int> uv_indices;    // 0-based texture coordinate index per corner; empty when no face has vt
  std::vector<int> face_line;     // the line of each face, for errors found later
  int num_vertices() const { return static_cast<int>(positions.size() / 3); }
  int num_faces() const { return static_cast<int>(face_start.size()) - 1; }
};

ObjPolygons read_obj_polygons(const std::string& path);

}  // namespace layers::geometry
