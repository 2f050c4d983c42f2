// layers/generate/imported_garment.h -- a scene's outfit made of users'
// own garment meshes (outfit entries `file:<mesh>`, import/garment_file.h)
// instead of templates, as LAYERS-H5 garment arrays of type `imported`.
//
// Each mesh is read, remeshed when its side file asks (`remesh: fit`: to
// garments.fit.edge_length, import/remesh.h) and checked
// (import/garment_file.h read_garment_mesh) and taken as modelled around our body in its T-pose for the scene's shape
// (arms along x, y up, facing +z, soles on y = 0; `layers tpose` writes
// that body). UVs: the file's, per face corner; without them a
// cylindrical parametrisation in metres about the vertical axis through
// the pelvis joint: u = angle x the garment's mean distance from the axis,
// v = height, the faces across the seam at the back (angle +-pi) unwrapped.
// All faces are panel 0. Attributes: the scene's drawn ones, replaced by
// those the side file gives.
//
// Refused before any simulation (InputError naming the mesh file, one
// line): a garment with vertices inside the T-pose body (nearest-vertex
// test, docs/metrics.md; the count and the body part most of them are
// nearest), and an outer garment with vertices inside an inner one (the
// same test against the inner garments, open edges not counting).
#pragma once

#include <vector>

#include "layers/data/sequence.h"
#include "layers/garment/garment_body.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"

namespace layers::generate {

// Reads and checks every garment file the config's outfits name, before
// any scene: the mesh (mesh_import.h, mesh_checks.h) and its side file,
// whose attributes must be among sim::GarmentAttributes' and in their
// ranges. Throws InputError naming the file on the first problem. Records
// the content hash of each mesh and side file in config.garments.files
// (what the saved generator.yaml compares on a resume).
void resolve_garment_files(GeneratorConfig& config);

// Whether the scene's outfit is made of garment files (all or none: the
// generator config refuses a mix).
bool has_imported_garments(const SceneSpec& spec);

// `edge_length`: garments.fit.edge_length, the target of `remesh: fit`.
std::vector<data::GarmentData> imported_outfit(const garment::TPoseBody& body, const SceneSpec& spec,
                                               double layer_reach, double edge_length);

// The cylindrical parametrisation above, per face corner: uv [3F,2] and
// uv_faces [F,3] (the identity). `axis`: a point on the vertical axis.
void cylindrical_uv(const geometry::TriMesh& mesh, const Eigen::Vector3d& axis, std::vector<float>& uv,
                    std::vector<std::int32_t>& uv_faces);

}  // namespace layers::generate
