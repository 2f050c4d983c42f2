// A user's garment entry and its side file (see garment_file.h).
#include "layers/import/garment_file.h"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <filesystem>

#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/core/yaml_text.h"

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
        throw InputError(g.side_file, key, "name, scale, self_contact or attributes", "'" + key + "'");
      }
    } catch (const YAML::Exception& e) {
      throw InputError(g.side_file, key, "a value of the right type", std::string("'") + e.what() + "'");
    }
  }
  return g;
}

}  // namespace layers::import
