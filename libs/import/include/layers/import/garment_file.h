// layers/import/garment_file.h -- a user's garment as a generator config
// names it: the entry `file:<mesh>` in an outfit's `inner` list or its
// `outer` (its layer is where it stands), the mesh read by mesh_import.h,
// and beside it an optional side file, the mesh's path with `.yaml` in
// place of its extension:
//
//   name: my_dress                    # default: the mesh file's stem
//   scale: 0.01                       # the file's units to metres (default 1)
//   self_contact: false               # collide with itself (default true)
//   attributes: {mass: 0.3, bending: 40}
//
// `attributes`: any of the seven LAYERS-H5 garment attributes (mass,
// tension, compression, shear, bending, friction, self_friction; docs/
// format.md); those not given are drawn from the config's
// garments.attributes as for a template. Paths are as written in the
// config, relative to the folder the command runs in.
#pragma once

#include <map>
#include <string>

namespace layers::import {

inline constexpr const char* kFilePrefix = "file:";

// Whether an outfit entry names a file ("file:<path>").
bool is_garment_file(const std::string& entry);

struct GarmentFile {
  std::string mesh;       // the mesh file's path
  std::string side_file;  // its .yaml, "" when there is none
  std::string name;
  double scale = 1.0;
  bool self_contact = true;                  // unknown shape: it may fold onto itself
  std::map<std::string, double> attributes;  // as given; checked by the generator
};

// Reads the entry's side file (when present). Throws InputError naming the
// side file for an unknown key, a non-positive scale, a self_contact that
// is not true or false, a non-finite or
// negative attribute, or a mesh file that does not exist.
GarmentFile read_garment_file(const std::string& entry);

}  // namespace layers::import
