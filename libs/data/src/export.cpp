// Exporting sequences to OBJ frames or PC2 caches (see export.h).
#include "layers/data/export.h"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <set>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/format.h"
#include "layers/data/glb.h"
#include "layers/data/obj.h"
#include "layers/data/pc2.h"

namespace layers::data {
namespace {

namespace fs = std::filesystem;

std::string file_safe(const std::string& text) {
  std::string out;
  for (char c : text) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' ? c : '_';
  return out;
}

// One exported mesh: its file-safe name, topology and where its positions
// are in a Window (garment < 0: the body).
struct MeshOut {
  std::string name;
  int garment;
  ObjMesh topology;  // faces (+ uv) only; positions filled per frame
  const std::vector<float>& positions(const Window& w) const {
    return garment < 0 ? w.body.positions : w.garments[static_cast<std::size_t>(garment)];
  }
};

std::vector<MeshOut> meshes_of(const SequenceStatic& statics) {
  std::vector<std::string> garment_names;
  for (const GarmentStatic& g : statics.garments) garment_names.push_back(g.name);
  const std::vector<std::string> names = mesh_file_names(garment_names);
  std::vector<MeshOut> meshes;
  meshes.push_back(MeshOut{names[0], -1, ObjMesh{{}, statics.body.faces, {}, {}}});
  for (std::size_t k = 0; k < statics.garments.size(); ++k) {
    const GarmentStatic& g = statics.garments[k];
    meshes.push_back(MeshOut{names[k + 1], static_cast<int>(k), ObjMesh{{}, g.faces, g.uv, g.uv_faces}});
  }
  return meshes;
}

}  // namespace

std::vector<std::string> mesh_file_names(const std::vector<std::string>& garment_names) {
  std::vector<std::string> names{"body"};
  std::set<std::string> used{"body"};
  for (std::size_t k = 0; k < garment_names.size(); ++k) {
    const std::string base = garment_names[k].empty() ? "garment" + std::to_string(k) : file_safe(garment_names[k]);
    std::string name = base;
    for (int n = 2; used.count(name); ++n) name = base + "_" + std::to_string(n);
    used.insert(name);
    names.push_back(name);
  }
  return names;
}

namespace {

std::string frame_text(std::int64_t frame) {
  char buffer[24];
  std::snprintf(buffer, sizeof(buffer), "%04lld", static_cast<long long>(frame));
  return buffer;
}

}  // namespace

ExportFormat parse_export_format(const std::string& text, const std::string& source) {
  if (text == "obj") return ExportFormat::Obj;
  if (text == "pc2") return ExportFormat::Pc2;
  if (text == "glb") return ExportFormat::Glb;
  throw InputError(source, "", "obj, pc2 or glb", "'" + text + "'");
}

std::vector<std::string> export_sequence(const Dataset& dataset, const std::string& id, ExportFormat format,
                                         std::int64_t first, std::int64_t last, const std::string& out_dir,
                                         std::int64_t glb_chunk) {
  const SequenceInfo& info = dataset.info(id);
  if (last < 0) last = info.n_frames;
  if (first < 0 || first >= last || last > info.n_frames) {
    throw InputError(info.shard, "/seq/" + id + " export range",
                     "[first,last) with 0 <= first < last <= " + std::to_string(info.n_frames),
                     "[" + std::to_string(first) + "," + std::to_string(last) + ")");
  }
  const auto statics = dataset.statics(id);
  std::vector<MeshOut> meshes = meshes_of(*statics);
  const std::string prefix = (fs::path(out_dir) / file_safe(id)).string() + "_";
  // Every file this export writes, checked before anything is: a file of
  // the same name already there is the user's, and is not replaced.
  std::vector<std::string> planned;
  if (format == ExportFormat::Glb) planned.push_back((fs::path(out_dir) / file_safe(id)).string() + ".glb");
  for (const MeshOut& mesh : meshes) {
    if (format == ExportFormat::Obj)
      for (std::int64_t t = first; t < last; ++t) planned.push_back(prefix + mesh.name + "_" + frame_text(t) + ".obj");
    if (format == ExportFormat::Pc2)
      planned.insert(planned.end(), {prefix + mesh.name + ".obj", prefix + mesh.name + ".pc2"});
  }
  for (const std::string& path : planned)
    if (fs::exists(fs::symlink_status(path)))
      throw InputError(path, "", "a name not taken in the output folder (an export replaces nothing)",
                       "a file of that name already there");
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir))
    throw InputError::message(out_dir, "", "cannot create the output folder: " + ec.message());
  std::vector<std::string> written;

  std::vector<std::unique_ptr<Pc2Writer>> caches;
  if (format == ExportFormat::Pc2) {
    for (const auto& mesh : meshes) {
      const auto n_points = static_cast<std::int32_t>(
          (mesh.garment < 0 ? info.body_vertices : info.garments[static_cast<std::size_t>(mesh.garment)].n_vertices));
      const Pc2Header header{n_points, static_cast<float>(first), 1.0f, static_cast<std::int32_t>(last - first)};
      caches.push_back(std::make_unique<Pc2Writer>(prefix + mesh.name + ".pc2", header));
    }
  }
  if (format == ExportFormat::Glb) {
    std::vector<GlbMesh> glb(meshes.size());
    for (std::size_t m = 0; m < meshes.size(); ++m) glb[m] = GlbMesh{meshes[m].name, meshes[m].topology.faces, {}};
    for (std::int64_t t = first; t < last; ++t) {
      const Window w = dataset.read_frames(id, t, 1);
      for (std::size_t m = 0; m < meshes.size(); ++m) glb[m].frames.push_back(meshes[m].positions(w));
    }
    const std::string path = (fs::path(out_dir) / file_safe(id)).string() + ".glb";
    write_text_atomic(path, glb_bytes(glb, static_cast<double>(kFps), glb_chunk));
    return {path};
  }
  for (std::int64_t t = first; t < last; ++t) {
    const Window w = dataset.read_frames(id, t, 1);
    for (std::size_t m = 0; m < meshes.size(); ++m) {
      MeshOut& mesh = meshes[m];
      if (format == ExportFormat::Obj || t == first) {
        mesh.topology.positions = mesh.positions(w);
        const std::string path =
            prefix + mesh.name + (format == ExportFormat::Obj ? "_" + frame_text(t) : std::string()) + ".obj";
        write_obj(path, mesh.topology);
        written.push_back(path);
      }
      if (format == ExportFormat::Pc2) caches[m]->append(mesh.positions(w).data());
    }
  }
  for (std::size_t m = 0; m < caches.size(); ++m) {
    caches[m]->commit();
    written.push_back(prefix + meshes[m].name + ".pc2");
  }
  return written;
}

}  // namespace layers::data
