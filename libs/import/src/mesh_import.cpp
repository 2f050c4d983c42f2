// Reading a user's mesh with assimp, welding seams (see mesh_import.h).
#include "layers/import/mesh_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <map>

#include "assimp_read.h"
#include "file_names.h"
#include "layers/core/error.h"
#include "layers/data/obj.h"

namespace layers::import {
namespace {

struct Collected {
  std::vector<std::array<float, 3>> positions;
  std::vector<std::array<float, 2>> uvs;  // when every mesh has them
  std::vector<std::array<int, 3>> faces;
  std::vector<std::int32_t> uv_faces;  // [F,3] into uvs
  bool all_uv = true;
};

Collected read_with_assimp(const std::string& path, double scale);
ImportedMesh welded(const std::string& path, const Collected& c);

void collect(const aiScene* scene, const aiNode* node, const aiMatrix4x4& parent, double scale, Collected& out) {
  const aiMatrix4x4 world = parent * node->mTransformation;
  for (unsigned k = 0; k < node->mNumMeshes; ++k) {
    const aiMesh* m = scene->mMeshes[node->mMeshes[k]];
    if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
    const int base = static_cast<int>(out.positions.size());
    const bool has_uv = m->HasTextureCoords(0);
    out.all_uv = out.all_uv && has_uv;
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const aiVector3D p = world * m->mVertices[v];
      out.positions.push_back(
          {static_cast<float>(p.x * scale), static_cast<float>(p.y * scale), static_cast<float>(p.z * scale)});
      out.uvs.push_back(has_uv ? std::array<float, 2>{m->mTextureCoords[0][v].x, m->mTextureCoords[0][v].y}
                               : std::array<float, 2>{0, 0});
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f) {
      const aiFace& face = m->mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines of a mixed mesh
      out.faces.push_back({base + static_cast<int>(face.mIndices[0]), base + static_cast<int>(face.mIndices[1]),
                           base + static_cast<int>(face.mIndices[2])});
    }
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) collect(scene, node->mChildren[c], world, scale, out);
}

// An OBJ through our own reader (data/obj.h), which keeps the file's
// vertex order: assimp's OBJ loader renumbers vertices by face corner, and
// the cloth solver's results depend on the order (docs/own-data.md).
Collected read_obj_file(const std::string& path, double scale) {
  const data::ObjMesh obj = data::read_obj(path);
  Collected c;
  for (std::size_t i = 0; i + 2 < obj.positions.size(); i += 3)
    c.positions.push_back({static_cast<float>(obj.positions[i] * scale),
                           static_cast<float>(obj.positions[i + 1] * scale),
                           static_cast<float>(obj.positions[i + 2] * scale)});
  for (std::size_t f = 0; f + 2 < obj.faces.size(); f += 3)
    c.faces.push_back({obj.faces[f], obj.faces[f + 1], obj.faces[f + 2]});
  c.all_uv = !obj.uv_faces.empty();
  if (c.all_uv) {
    for (std::size_t i = 0; i + 1 < obj.uv.size(); i += 2) c.uvs.push_back({obj.uv[i], obj.uv[i + 1]});
    c.uv_faces = obj.uv_faces;
  }
  return c;
}

bool is_obj(const std::string& path) { return lower_extension(path) == ".obj"; }

Collected read_with_assimp(const std::string& path, double scale) {
  Assimp::Importer importer;
  // Triangulate polygons; no vertex joining by assimp (we weld by position
  // below, which also joins vertices split at UV seams).
  const aiScene* scene = detail::read_with_assimp(importer, path, aiProcess_Triangulate | aiProcess_SortByPType,
                                                  "a mesh file assimp reads");
  Collected c;
  collect(scene, scene->mRootNode, aiMatrix4x4(), scale, c);
  if (c.all_uv)
    for (const auto& f : c.faces) c.uv_faces.insert(c.uv_faces.end(), {f[0], f[1], f[2]});  // UVs per file vertex
  return c;
}

ImportedMesh welded(const std::string& path, const Collected& c) {
  ImportedMesh out;
  out.file = path;
  out.file_vertices = static_cast<int>(c.positions.size());
  std::map<std::array<float, 3>, int> index;
  std::vector<int> welded(c.positions.size());
  std::vector<std::array<float, 3>> kept;
  for (std::size_t i = 0; i < c.positions.size(); ++i) {
    const auto [it, added] = index.emplace(c.positions[i], static_cast<int>(kept.size()));
    if (added) kept.push_back(c.positions[i]);
    welded[i] = it->second;
  }
  out.mesh.vertices.resize(static_cast<Eigen::Index>(kept.size()), 3);
  for (std::size_t i = 0; i < kept.size(); ++i)
    for (int a = 0; a < 3; ++a) out.mesh.vertices(static_cast<Eigen::Index>(i), a) = kept[i][a];
  out.mesh.faces.resize(static_cast<Eigen::Index>(c.faces.size()), 3);
  for (std::size_t f = 0; f < c.faces.size(); ++f)
    for (int a = 0; a < 3; ++a) out.mesh.faces(static_cast<Eigen::Index>(f), a) = welded[c.faces[f][a]];
  if (c.all_uv) {
    for (const auto& uv : c.uvs) out.uv.insert(out.uv.end(), {uv[0], uv[1]});
    out.uv_faces = c.uv_faces;
  }
  return out;
}

}  // namespace

ImportedMesh import_mesh(const std::string& path, double scale) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path, "", "a mesh file (OBJ, glTF/GLB, FBX, ...)", "no such file");
  if (!(scale > 0)) throw InputError(path, "scale", "a positive factor to metres", std::to_string(scale));
  Collected c = is_obj(path) ? read_obj_file(path, scale) : read_with_assimp(path, scale);
  if (c.faces.empty()) throw InputError(path, "", "a mesh with triangles", "no triangle in the file");
  // Before welding: a NaN would compare equal to any position.
  for (std::size_t i = 0; i < c.positions.size(); ++i)
    for (float x : c.positions[i])
      if (!std::isfinite(x))
        throw InputError(path, "vertices", "finite positions", "a non-finite value in vertex " + std::to_string(i));
  return welded(path, c);
}

}  // namespace layers::import
