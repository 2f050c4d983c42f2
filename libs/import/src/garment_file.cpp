// A user's garment entry and its side file (see garment_file.h).
#include "layers/import/garment_file.h"

#include <spdlog/spdlog.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>
#include <mutex>
#include <string>
#include <vector>

#include "layers/core/checksum.h"
#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/core/yaml_text.h"
#include "layers/import/mesh_checks.h"
#include "layers/import/remesh.h"

namespace layers::import {

bool is_garment_file(const std::string& entry) { return entry.rfind(kFilePrefix, 0) == 0; }

GarmentFile read_garment_file(const std::string& entry) {
  namespace fs = std::filesystem;
  if (!is_garment_file(entry)) throw InputError(entry, "", "a garment file entry file:<mesh>", "'" + entry + "'");
  GarmentFile g;
  g.mesh = entry.substr(std::string(kFilePrefix).size());
  if (g.mesh.empty() || !fs::is_regular_file(g.mesh))
    throw InputError(g.mesh, "", "a garment mesh file (OBJ, glTF/GLB, FBX, ...)", "no such file");
  g.name = fs::path(g.mesh).stem().string();
  const fs::path side = fs::path(g.mesh).replace_extension(".yaml");
  if (!fs::is_regular_file(side)) return g;
  g.side_file = side.string();
  const YAML::Node root = parse_yaml(read_text_file(g.side_file), g.side_file);
  if (!root.IsMap() && !root.IsNull())
    throw InputError(g.side_file, "", "a mapping (name, scale, attributes)", "not a mapping");
  for (const auto& item : root) {
    std::string key = "(a key)";
    try {
      key = item.first.as<std::string>();
      if (key == "name") {
        g.name = item.second.as<std::string>();
        if (g.name.empty()) throw InputError(g.side_file, key, "a non-empty name", "''");
      } else if (key == "scale") {
        g.scale = item.second.as<double>();
        if (!(g.scale > 0) || !std::isfinite(g.scale))
          throw InputError(g.side_file, key, "a positive factor to metres", std::to_string(g.scale));
      } else if (key == "self_contact") {
        g.self_contact = item.second.as<bool>();
      } else if (key == "remesh") {
        const std::string text = item.second.as<std::string>();
        if (text == "fit") {
          g.remesh = kRemeshToFit;
        } else if (text == "off" || text == "false") {
          g.remesh = 0.0;
        } else {
          g.remesh = item.second.as<double>();
          if (!(g.remesh > 0.0005 && g.remesh < 0.5))
            throw InputError(g.side_file, key, "fit, off, or an edge length in metres in (0.0005, 0.5)",
                             "'" + text + "'");
        }
      } else if (key == "attributes") {
        if (!item.second.IsMap()) throw InputError(g.side_file, key, "a mapping of attribute values", "not a mapping");
        for (const auto& a : item.second) {
          const std::string name = a.first.as<std::string>();
          const double v = a.second.as<double>();
          if (!std::isfinite(v) || v < 0)
            throw InputError(g.side_file, "attributes." + name, "a finite value >= 0", std::to_string(v));
          g.attributes[name] = v;
        }
      } else {
        throw InputError(g.side_file, key, "name, scale, self_contact, remesh or attributes", "'" + key + "'");
      }
    } catch (const YAML::Exception& e) {
      throw InputError(g.side_file, key, "a value of the right type", std::string("'") + e.what() + "'");
    }
  }
  return g;
}

namespace {

// The meshes read so far in this process, by what they were made from (the
// file's path and bytes, its scale, the remesh target): the generator reads
// a garment file when it loads the config and again for every scene, and a
// remesh takes a while and logs a line. A changed file has other bytes and
// is read again.
struct ReadMesh {
  std::string key;
  ImportedMesh mesh;
};
std::mutex read_mutex;
std::vector<ReadMesh> read_meshes;

}  // namespace

ImportedMesh read_garment_mesh(const GarmentFile& file, double fit_edge_length) {
  const double target = file.remesh > 0.0 ? file.remesh : file.remesh != 0.0 ? fit_edge_length : 0.0;
  std::string key = file.mesh + '\n' + content_hash(read_text_file(file.mesh)) + '\n';
  key += std::to_string(file.scale) + ' ' + std::to_string(target) + ' ' + std::to_string(fit_edge_length);
  {
    const std::lock_guard<std::mutex> lock(read_mutex);
    for (const ReadMesh& r : read_meshes)
      if (r.key == key) return r.mesh;
  }
  ImportedMesh m = import_mesh(file.mesh, file.scale);
  if (file.remesh != 0.0) {
    RemeshReport r;
    m = remesh(m, target, 5, &r);
    spdlog::info("{}: remeshed to {:.1f} mm edges: {} faces -> {}, shortest edge {:.1f} -> {:.1f} mm", file.mesh,
                 1000 * target, r.faces_before, r.faces_after, 1000 * r.shortest_before, 1000 * r.shortest_after);
  } else {
    double shortest = 0, mean = 0;
    edge_lengths(m.mesh, shortest, mean);
    if (shortest < 0.25 * fit_edge_length)
      spdlog::warn(
          "{}: edges down to {:.1f} mm (mean {:.1f} mm) against the simulator's {:.1f} mm: short edges make the "
          "stretch cap hard to keep; `remesh: fit` in {} remeshes it",
          file.mesh, 1000 * shortest, 1000 * mean, 1000 * fit_edge_length,
          file.side_file.empty() ? std::filesystem::path(file.mesh).replace_extension(".yaml").string()
                                 : file.side_file);
  }
  check_cloth_mesh(m.mesh, file.mesh);
  const std::lock_guard<std::mutex> lock(read_mutex);
  read_meshes.push_back({key, m});
  return m;
}

}  // namespace layers::import
