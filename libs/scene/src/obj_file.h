// obj_file.h (private to layers::scene) -- a Wavefront OBJ reader for the
// MakeHuman base mesh: vertex positions and polygon faces (position indices
// only; `v/vt/vn` forms and negative indices accepted), nothing else.
#pragma once

#include <string>
#include <vector>

namespace layers::scene {

struct ObjPolygons {
  std::vector<double> positions;  // 3 per vertex, as stored
  std::vector<int> face_start;    // face f uses indices[face_start[f] .. face_start[f+1])
  std::vector<int> indices;       // 0-based vertex indices
  int num_vertices() const { return static_cast<int>(positions.size() / 3); }
  int num_faces() const { return static_cast<int>(face_start.size()) - 1; }
};

// Throws InputError naming file and line for malformed lines.
ObjPolygons read_obj(const std::string& path);

}  // namespace layers::scene
