// layers/import/body_import.h -- a user's own body and its motion, read
// from their files, in plain arrays (the generator turns them into a body
// of ours: generate/own_body.h):
//
// - a rigged body (glTF/GLB, FBX, Collada, ... through assimp): every
//   skinned mesh of the file as one mesh in its bind pose, welded where
//   the file split vertices at seams (same position, same weights), its
//   skeleton (the nodes its meshes are bound to, each parented to its
//   nearest bound ancestor; one root), the four largest weights per
//   vertex, and one of its animations sampled at 30 frames a second as
//   each joint's world rotation relative to the bind pose and world
//   position (the `body/joints` convention of LAYERS-H5). Joint names lose
//   a namespace prefix ("mixamorig:Hips" -> "Hips").
// - a mesh sequence: a POINTCACHE2 file with an OBJ giving its faces and
//   rest pose (one sample per frame), or a folder of OBJ files (one per
//   frame, in name order with numbers compared as numbers, the same faces
//   in each; the first is the rest pose unless an OBJ is given), frames at
//   30 a second. It has one joint, `Root`, that carries
//   every vertex: per frame the rigid motion closest to the vertices'
//   (least squares from the rest pose).
//
// Lengths are multiplied by `scale` (the file's units to metres). Each
// problem is one InputError naming the file.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <string>
#include <vector>

#include "layers/geometry/mesh.h"

namespace layers::import {

// A body is 0.5-2.5 m tall (y extent): a file in centimetres fails.
inline constexpr double kMinBodyHeight = 0.5, kMaxBodyHeight = 2.5;

struct BodyFrame {
  std::vector<Eigen::Quaterniond> rotation;  // per joint, world rotation relative to the bind pose
  std::vector<Eigen::Vector3d> position;     // per joint, world position
};

struct ImportedBody {
  std::string file;
  geometry::TriMesh rest;  // the bind pose (rigged) or rest pose (sequence), metres
  std::vector<std::string> joint_names;
  std::vector<int> parents;                                              // -1 for joint 0 only; parents come first
  std::vector<Eigen::Vector3d> joint_rest;                               // world joint positions in the rest pose
  Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor> skin_index;     // unused slots: joint 0, weight 0
  Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor> skin_weight;  // sums to 1 per vertex
  std::string animation;                   // the animation's name (rigged), "" for a sequence
  std::vector<BodyFrame> frames;           // the motion at 30 fps (empty: the file has no animation)
  std::vector<geometry::Points> vertices;  // a sequence's vertices per frame (empty for a rigged body)
  int skipped_meshes = 0;                  // meshes of a rigged file bound to no joint (left out)
  // The most a joint other than the root strays from its offset to its
  // parent (m, at most 5 mm: taken at its offset), which and when.
  double joint_drift = 0;
  std::string drift_joint;
  int drift_frame = -1;
  bool rigged() const { return vertices.empty(); }
  int num_frames() const { return static_cast<int>(frames.size()); }
};

// Whether `path` is a mesh sequence (a .pc2 file or a folder) rather than
// a rigged file.
bool is_mesh_sequence(const std::string& path);

// A rigged body. `animation`: the name of the animation to sample ("" =
// the file's first; a file without any gives no frames). Refused: a
// missing or unreadable file, no skinned mesh, more than one root joint,
// a vertex with no weight, a joint that scales or shears in a frame (the
// skinning here is rigid per joint), a joint other than the root that
// leaves its fixed offset from its parent by more than 5 mm (less is
// taken at the offset: joint_drift), two joints of one name, an
// animation longer than 3,600 s or of more than 4,000,000 joints x
// frames at 30 fps (checked before sampling), a body outside kMin/kMaxBodyHeight, an
// animation name the file does not hold, a non-finite value.
ImportedBody import_rigged_body(const std::string& path, double scale = 1.0, const std::string& animation = "");

// A mesh sequence: `path` a .pc2 file (`mesh` an OBJ, required) or a
// folder of .obj files (`mesh` optional). Refused: a missing file, a frame
// whose vertex count or faces differ from the mesh's, fewer than one
// frame, a .pc2 sample rate other than 1, a body outside the height
// range, a non-finite value.
ImportedBody import_mesh_sequence(const std::string& path, const std::string& mesh = "", double scale = 1.0);

// Either of the above, by is_mesh_sequence(path).
ImportedBody import_body(const std::string& path, const std::string& mesh = "", double scale = 1.0,
                         const std::string& animation = "");

}  // namespace layers::import
