// layers/data/sequence.h -- in-memory sequences of the LAYERS-H5 format.
//
// Arrays are flat, row-major std::vectors whose shape is written next to
// them (symbols as in format.h). A sequence splits into what has no time
// axis (the *Static structs: topology, rest shape, UVs, skinning) and what
// has one (BodyFrames, WindData, garment positions), so that the streaming
// reader can cache the former and read windows of the latter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace layers::data {

struct BodyStatic {
  std::vector<std::int32_t> faces;          // [Fb,3]
  std::vector<std::string> joint_names;     // [J]
  std::vector<std::int32_t> joint_parents;  // [J], -1 for a root joint
  std::vector<std::int32_t> skin_index;     // [Vb,4] joint indices
  std::vector<float> skin_weight;           // [Vb,4]
  // [J,3,4] joint transforms [R|p] of the T-pose the garments' rest shapes
  // were made in (convention of body/joints); empty when absent.
  std::vector<float> tpose_joints;

  std::int64_t n_vertices() const { return static_cast<std::int64_t>(skin_index.size() / 4); }
  std::int64_t n_faces() const { return static_cast<std::int64_t>(faces.size() / 3); }
  std::int64_t n_joints() const { return static_cast<std::int64_t>(joint_names.size()); }
};

// Per-frame body arrays of some number of frames n.
struct BodyFrames {
  std::vector<float> positions;  // [n,Vb,3]
  std::vector<float> root;       // [n,3] pelvis translation
  std::vector<float> root_rot;   // [n,4] pelvis orientation w,x,y,z
  std::vector<float> joints;     // [n,J,3,4] world transform of each joint
};

struct BodyData : BodyStatic, BodyFrames {};

// Per-frame wind of some number of frames n.
struct WindData {
  std::vector<float> rotation;  // [n,4] w,x,y,z; rotates +z onto the wind direction
  std::vector<float> strength;  // [n] 0..400 (Blender units)
};

struct GarmentStatic {
  std::string name;
  std::string type;                          // see garment_types()
  int layer = 0;                             // 0 inner, 1 outer
  std::map<std::string, double> attributes;  // mass, tension, ...
  std::vector<std::int32_t> faces;           // [F,3]
  std::vector<float> rest;                   // [V,3]
  std::vector<float> uv;                     // [U,2]
  std::vector<std::int32_t> uv_faces;        // [F,3] indices into uv
  std::vector<std::int32_t> panel;           // [F] sewing-pattern panel of each face

  std::int64_t n_vertices() const { return static_cast<std::int64_t>(rest.size() / 3); }
  std::int64_t n_faces() const { return static_cast<std::int64_t>(faces.size() / 3); }
  std::int64_t n_uv() const { return static_cast<std::int64_t>(uv.size() / 2); }
};

struct GarmentData : GarmentStatic {
  std::vector<float> positions;  // [T,V,3]
};

// One whole sequence, as written by the generator and read back by
// Dataset::read_sequence.
struct SequenceData {
  std::string id;  // group name: non-empty, no '/', not "." or ".."
  std::int64_t n_frames = 0;
  std::string motion;
  std::uint64_t seed = 0;
  std::vector<std::string> tags;        // e.g. {"T+W"}
  std::map<std::string, double> shape;  // body shape parameters
  BodyData body;
  WindData wind;
  std::vector<GarmentData> garments;
};

// Everything of a sequence that has no time axis (cached by the reader).
struct SequenceStatic {
  std::string id;
  std::int64_t n_frames = 0;
  BodyStatic body;
  std::vector<GarmentStatic> garments;
  // Heap bytes held (for the cache's accounting).
  std::size_t bytes() const;
};

struct GarmentInfo {
  std::string group;  // HDF5 group name under garments/ ("0", "1", ...)
  std::string name, type;
  int layer = 0;
  std::map<std::string, double> attributes;
  std::int64_t n_vertices = 0, n_faces = 0, n_uv = 0;
};

// What the reader's index knows of a sequence without reading any array.
struct SequenceInfo {
  std::string id;
  std::string shard;  // path of the shard file
  std::int64_t n_frames = 0;
  std::string motion;
  std::uint64_t seed = 0;
  std::vector<std::string> tags;
  std::map<std::string, double> shape;
  std::int64_t body_vertices = 0, body_faces = 0, n_joints = 0;
  bool has_tpose_joints = false;  // the optional body/tpose_joints is present
  std::vector<GarmentInfo> garments;
};

// Frames [first_frame, first_frame + n_frames) of one sequence. A window
// read with read_window(id, start, history, horizon) has
// first_frame = start - history and n_frames = history + horizon + 1.
struct Window {
  std::string id;
  std::int64_t first_frame = 0, n_frames = 0;
  std::int64_t start = 0, history = 0, horizon = 0;
  BodyFrames body;
  WindData wind;
  std::vector<std::vector<float>> garments;  // one [n,V,3] per garment
};

// Checks that the arrays of `seq` have consistent sizes (T = n_frames, the
// same V across rest/positions, J across joints/names/parents, ...), that
// indices are in range (faces, uv_faces, skin_index, joint_parents), that
// garment types and layers are known and that the id is a valid group
// name. Throws InputError naming `file` and the object path the bad array
// would have (e.g. /seq/abc/garments/0/positions). Values are not scanned
// for NaN (the validator does that on files).
void check_sequence(const SequenceData& seq, const std::string& file);

// The index rules of check_sequence on what a reader read of a sequence's
// static arrays (faces, skin_index, joint_parents, uv_faces, panel), so a
// bad index is blamed on the file it came from, not on a later output.
void check_static_indices(const SequenceStatic& seq, const std::string& file);

}  // namespace layers::data
