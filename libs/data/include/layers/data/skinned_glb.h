// layers/data/skinned_glb.h -- a body with its skeleton, skin weights and
// motion as one binary glTF 2.0 file (GLB): a rig that Blender and
// three.js animate, and that a generator config's `body.own` reads back
// (import/body_import.h). Metres, y up, the format's 30 fps.
//
// Every joint is a node whose bind rotation is the identity (joint frames
// aligned with the world axes in the bind pose, as in body/joints): its
// translation is its bind offset from its parent (the root's: its bind
// position), its inverse bind matrix the negated bind position. Per frame
// a joint node turns by R_parent^T R_j (R the world rotations relative to
// the bind pose) and the root moves to its world position; one LINEAR
// sampler per joint, named animation "motion". The mesh node is skinned
// with the four influences per vertex.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace layers::data {

struct SkinnedBody {
  std::string name = "body";
  std::vector<float> rest;                  // [V,3] the bind pose
  std::vector<std::int32_t> faces;          // [F,3]
  std::vector<std::string> joint_names;     // [J]
  std::vector<std::int32_t> joint_parents;  // [J], -1 for joint 0 only; parents first
  std::vector<float> rest_joints;           // [J,3] bind positions
  std::vector<std::int32_t> skin_index;     // [V,4]
  std::vector<float> skin_weight;           // [V,4]
  std::vector<float> joints;                // [T,J,3,4] world [R|p] relative to the bind pose; empty: no motion
};

// The GLB's bytes. Throws layers::Error on inconsistent sizes, a joint
// whose parent does not come before it, or a single animated frame.
std::string skinned_glb_bytes(const SkinnedBody& body, double fps);

}  // namespace layers::data
