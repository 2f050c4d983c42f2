// Skeleton queries and forward kinematics (see skeleton.h).
#include "layers/body/skeleton.h"

#include "layers/core/error.h"

namespace layers::body {

int Skeleton::index(const std::string& name) const {
  for (int j = 0; j < num_joints(); ++j)
    if (names[j] == name) return j;
  return -1;
}

int Skeleton::require(const std::string& name) const {
  int j = index(name);
  if (j < 0) throw Error("skeleton has no joint named '" + name + "'");
  return j;
}

std::vector<int> Skeleton::children(int joint) const {
  std::vector<int> out;
  for (int j = 0; j < num_joints(); ++j)
    if (parents[j] == joint) out.push_back(j);
  return out;
}

Pose rest_pose(const Skeleton& skeleton) {
  Pose p;
  p.local.assign(skeleton.num_joints(), Quat::Identity());
  p.root = skeleton.rest_head.empty() ? Vec3::Zero() : skeleton.rest_head[0];
  return p;
}

Pose blend(const Pose& a, const Pose& b, double t) {
  Pose out;
  out.local.resize(a.local.size());
  for (std::size_t j = 0; j < a.local.size(); ++j) out.local[j] = slerp(a.local[j], b.local[j], t);
  out.root = (1.0 - t) * a.root + t * b.root;
  return out;
}

JointTransforms forward_kinematics(const Skeleton& skeleton, const Pose& pose) {
  const int n = skeleton.num_joints();
  if (static_cast<int>(pose.local.size()) != n)
    throw Error("pose has " + std::to_string(pose.local.size()) + " joints, skeleton " + std::to_string(n));
  JointTransforms t;
  t.rotation.resize(n);
  t.position.resize(n);
  for (int j = 0; j < n; ++j) {
    int p = skeleton.parents[j];
    if (p < 0) {
      t.rotation[j] = pose.local[j].normalized();
      t.position[j] = pose.root;
    } else {
      t.rotation[j] = (t.rotation[p] * pose.local[j]).normalized();
      t.position[j] = t.position[p] + t.rotation[p] * (skeleton.rest_head[j] - skeleton.rest_head[p]);
    }
  }
  return t;
}

Pose pose_from_world(const Skeleton& skeleton, const std::vector<Quat>& world, const Vec3& root) {
  Pose pose;
  pose.root = root;
  pose.local.resize(world.size());
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    int p = skeleton.parents[j];
    pose.local[j] = p < 0 ? world[j] : (world[p].conjugate() * world[j]).normalized();
  }
  return pose;
}

Quat from_bone_axes(const Skeleton& skeleton, int joint, const Quat& bone_local) {
  Quat frame(skeleton.bone_frame[joint]);
  return (frame * bone_local * frame.conjugate()).normalized();
}

}  // namespace layers::body
