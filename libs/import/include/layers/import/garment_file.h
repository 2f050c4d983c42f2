// layers/import/garment_file.h -- a user's garment as a generator config
// names it: the entry `file:<mesh>` in an outfit's `inner` list or its
// `outer` (its layer is where it stands), the mesh read by mesh_import.h,
// and beside it an optional side file, the mesh's path with `.yaml` in
// place of its extension:
//
//   name: my_dress                    # default: the mesh file's stem
//   scale: 0.01                       # the file's units to metres (default 1)
//   self_contact: false               # collide with itself (default true)
//   remesh: fit                       # remesh to garments.fit.edge_length, or to a length in m (default off)
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

#include "layers/import/mesh_import.h"

namespace layers::import {

inline constexpr const char* kFilePrefix = "file:";
inline constexpr double kRemeshToFit = -1.0;

// Whether an outfit entry names a file ("file:<path>").
bool is_garment_file(const std::string& entry);

struct GarmentFile {
  std::string mesh;       // the mesh file's path
  std::string side_file;  // its .yaml, "" when there is none
  std::string name;
  double scale = 1.0;
  bool self_contact = true;  // unknown shape: it may fold onto itself
  // Remeshing (remesh.h) before the checks: 0 off, > 0 to that edge
  // length (m), kRemeshToFit to the config's garments.fit.edge_length.
  double remesh = 0.0;
  std::map<std::string, double> attributes;  // as given; checked by the generator
};

// Reads the entry's side file (when present). Throws InputError naming the
// side file for an unknown key, a non-positive scale, a self_contact that
// is not true or false, a non-finite or
// negative attribute, or a mesh file that does not exist.
GarmentFile read_garment_file(const std::string& entry);

// The garment's mesh as the simulator takes it: read (mesh_import.h) at
// the file's scale, remeshed when the side file asks (to `fit_edge_length`
// for `remesh: fit`), and checked as cloth (mesh_checks.h). Without
// remeshing, a mesh with edges shorter than a quarter of
// `fit_edge_length` gets a warning naming the side file's `remesh` (such
// edges make the stretch cap hard to keep). A process reads each file once
// for the same bytes, scale and target: later calls return that mesh
// without reading, remeshing or logging again (a changed file is read anew).
ImportedMesh read_garment_mesh(const GarmentFile& file, double fit_edge_length);

}  // namespace layers::import
