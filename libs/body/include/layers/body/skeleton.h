// layers/body/skeleton.h -- the posed skeleton.
//
// Conventions (shared by BVH retargeting, procedural motions and the
// LAYERS-H5 `body/joints` arrays):
// - Joint j sits at the head of bone j; joint 0 (Hips) is the root.
//   Parents come before their children.
// - A Pose holds, per joint, a rotation *relative to the rest pose*
//   expressed in the parent's world-aligned frame (the frames of all
//   joints coincide with the world axes in the rest pose, as in BVH), and
//   the world position of the root joint.
// - Forward kinematics gives each joint's world rotation relative to rest,
//   R_j = R_parent * local_j, and world position
//   p_j = p_parent + R_parent * (rest_j - rest_parent).
//   A rest-pose point x attached to joint j moves to R_j (x - rest_j) + p_j.
// - The Blender bone frames (`bone_frame`, y axis along the bone, x/z set
//   by the bone roll) are only used to read per-bone Euler angles such as
//   the MPFB2 T-pose file.
#pragma once

#include <string>
#include <vector>

#include "layers/body/rotation.h"

namespace layers::body {

struct Skeleton {
  std::vector<std::string> names;
  std::vector<int> parents;      // -1 for the root
  std::vector<Vec3> rest_head;   // joint positions in the rest pose (world, metres)
  std::vector<Vec3> rest_tail;   // bone tails in the rest pose
  std::vector<Mat3> bone_frame;  // Blender bone axes (columns) in world coordinates

  int num_joints() const { return static_cast<int>(names.size()); }
  // Joint index by name, or -1.
  int index(const std::string& name) const;
  // Joint index by name; throws layers::Error when absent.
  int require(const std::string& name) const;
  std::vector<int> children(int joint) const;
  // Length of the bone from joint j to its tail.
  double bone_length(int joint) const { return (rest_tail[joint] - rest_head[joint]).norm(); }
};

struct Pose {
  std::vector<Quat> local;   // per joint, relative to rest, in the parent's frame
  Vec3 root = Vec3::Zero();  // world position of joint 0
};

// All rotations identity, root at its rest position.
Pose rest_pose(const Skeleton& skeleton);

// Interpolates two poses: slerp per joint, lerp of the root.
Pose blend(const Pose& a, const Pose& b, double t);

struct JointTransforms {
  std::vector<Quat> rotation;  // world rotation relative to the rest pose
  std::vector<Vec3> position;  // world joint position
};

JointTransforms forward_kinematics(const Skeleton& skeleton, const Pose& pose);

// The pose whose forward kinematics gives the world rotations `world`
// (relative to rest) with the root at `root`.
Pose pose_from_world(const Skeleton& skeleton, const std::vector<Quat>& world, const Vec3& root);

// Converts a rotation in Blender bone-local axes (pose-bone rotation) of
// joint j into this file's parent-frame convention: frame * q * frame^-1.
Quat from_bone_axes(const Skeleton& skeleton, int joint, const Quat& bone_local);

}  // namespace layers::body
