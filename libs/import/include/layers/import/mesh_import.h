// layers/import/mesh_import.h -- a user's mesh file as one triangle mesh,
// read with assimp (Debian's 5.2: OBJ, glTF 2.0 / GLB, FBX, Collada, PLY,
// STL, ...): every mesh of the file's scene with its node transforms
// applied, polygons triangulated, vertices the file split at seams (UV or
// normal seams: the same position stored twice) welded back into one, and
// the first UV channel kept per face corner. Positions are multiplied by
// `scale` (the file's units to metres); axes are kept as the file has
// them (our format is y up, as glTF and Blender's OBJ export are).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/geometry/mesh.h"

namespace layers::import {

struct ImportedMesh {
  std::string file;
  geometry::TriMesh mesh;              // welded vertices, triangles
  std::vector<float> uv;               // [U,2]; empty when the file has no UVs
  std::vector<std::int32_t> uv_faces;  // [F,3] into uv; empty with uv
  int file_vertices = 0;               // vertices as the file stores them (before welding)
};

// Throws InputError (one line naming the file) when the file is missing,
// cannot be read, holds no triangle or a non-finite position. UVs are kept
// only when every mesh of the file has them (else none, and the generator
// parametrises the garment itself).
ImportedMesh import_mesh(const std::string& path, double scale = 1.0);

}  // namespace layers::import
