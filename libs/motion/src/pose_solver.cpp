// Target-driven posing: leg IK, arm aiming (see pose_solver.h).
#include "pose_solver.h"

#include <algorithm>
#include <cmath>

namespace layers::motion {
namespace {

constexpr double kMaxReach = 0.9995;  // IK never straightens a leg fully (keeps the knee direction defined)

body::Vec3 perpendicular_part(const body::Vec3& v, const body::Vec3& axis) { return v - v.dot(axis) * axis; }

}  // namespace

PoseSolver::PoseSolver(const body::Body& body) : body_(body) {
  const body::Skeleton& sk = body.skeleton;
  const char* legs[2][5] = {{"LHipJoint", "LeftUpLeg", "LeftLeg", "LeftFoot", "LeftToeBase"},
                            {"RHipJoint", "RightUpLeg", "RightLeg", "RightFoot", "RightToeBase"}};
  for (int s = 0; s < 2; ++s) {
    Leg& l = leg_[s];
    l.hip_joint = sk.require(legs[s][0]);
    l.up = sk.require(legs[s][1]);
    l.knee = sk.require(legs[s][2]);
    l.foot = sk.require(legs[s][3]);
    l.toe = sk.require(legs[s][4]);
    l.hip_rest = sk.rest_head[l.up];
    l.knee_rest = sk.rest_head[l.knee];
    l.ankle_rest = sk.rest_head[l.foot];
    l.ball_rest = sk.rest_head[l.toe];
    l.ball_rest.y() = 0.0;
    l.l1 = (l.knee_rest - l.hip_rest).norm();
    l.l2 = (l.ankle_rest - l.knee_rest).norm();
  }
  const char* arms[2][3] = {{"LeftShoulder", "LeftArm", "LeftForeArm"}, {"RightShoulder", "RightArm", "RightForeArm"}};
  for (int s = 0; s < 2; ++s) {
    Arm& a = arm_[s];
    a.clavicle = sk.require(arms[s][0]);
    a.upper = sk.require(arms[s][1]);
    a.fore = sk.require(arms[s][2]);
    const body::Vec3 u = sk.rest_head[a.fore] - sk.rest_head[a.upper];
    const body::Vec3 f = sk.rest_tail[a.fore] - sk.rest_head[a.fore];
    a.upper_dir = u.normalized();
    a.elbow_axis = u.cross(f).normalized();
    a.rest_elbow = std::acos(std::clamp(u.normalized().dot(f.normalized()), -1.0, 1.0));
  }
  pelvis_rest_ = sk.rest_head[0];
  spine_[0] = sk.require("LowerBack");
  spine_[1] = sk.require("Spine");
  spine_[2] = sk.require("Spine1");
  neck_[0] = sk.require("Neck");
  neck_[1] = sk.require("Neck1");
  neck_[2] = sk.require("Head");
  chest_ = spine_[2];
}

double PoseSolver::standing_pelvis_height(double reach, double lateral) const {
  const Leg& l = leg_[0];
  const double r = reach * (l.l1 + l.l2);
  return l.ankle_rest.y() + std::sqrt(std::max(0.0, r * r - lateral * lateral)) + (pelvis_rest_.y() - l.hip_rest.y());
}

body::Vec3 PoseSolver::hip_position(const PoseTargets& t, int side) const {
  const body::Quat root = body::rot_y(t.yaw) * body::rot_x(t.pitch) * body::rot_z(t.roll);
  return t.pelvis + root * (leg_[side].hip_rest - pelvis_rest_);
}

body::Vec3 PoseSolver::ankle_target(const FootState& f, int side) const {
  const Leg& l = leg_[side];
  return f.ball + (body::rot_y(f.yaw) * body::rot_x(f.pitch)) * (l.ankle_rest - l.ball_rest);
}

double PoseSolver::pelvis_drop_needed(const PoseTargets& t, double reach) const {
  double drop = 0.0;
  for (int s = 0; s < 2; ++s) {
    if (!t.feet[s].planted) continue;
    const body::Vec3 d = ankle_target(t.feet[s], s) - hip_position(t, s);
    const double r = reach * leg_length();
    const double horizontal2 = d.x() * d.x() + d.z() * d.z();
    if (d.squaredNorm() <= r * r || horizontal2 >= r * r) continue;
    // Lower the hip until |d| = r: (-d.y - drop)^2 + horizontal2 = r^2.
    drop = std::max(drop, -d.y() - std::sqrt(r * r - horizontal2));
  }
  return std::max(0.0, drop);
}

body::Pose PoseSolver::solve(const PoseTargets& t) const {
  const body::Skeleton& sk = body_.skeleton;
  const int n = sk.num_joints();
  std::vector<body::Quat> world(n, body::Quat::Identity());
  std::vector<bool> done(n, false);
  auto set = [&](int j, const body::Quat& q) {
    world[j] = q.normalized();
    done[j] = true;
  };

  const body::Quat root = body::rot_y(t.yaw) * body::rot_x(t.pitch) * body::rot_z(t.roll);
  set(0, root);
  // Spine and head: the totals spread evenly over three joints each.
  body::Quat q = root;
  for (int j : spine_) {
    q = q * body::rot_y(t.spine_twist / 3) * body::rot_x(t.spine_flex / 3) * body::rot_z(t.spine_bend / 3);
    set(j, q);
  }
  for (int j : neck_) {
    q = q * body::rot_y(t.head_yaw / 3) * body::rot_x(t.head_pitch / 3);
    set(j, q);
  }
  const body::Quat chest = world[chest_];

  // Arms: upper arm aimed in the chest frame, elbow hinged about its axis.
  for (int s = 0; s < 2; ++s) {
    const Arm& a = arm_[s];
    const ArmAngles& g = t.arms[s];
    const double sign = s == 0 ? 1.0 : -1.0;
    set(a.clavicle, chest * body::rot_z(sign * g.clavicle));
    const body::Vec3 u0(sign * std::sin(g.abduction), -std::cos(g.abduction), 0.0);
    const body::Vec3 n0(-std::cos(g.abduction), -sign * std::sin(g.abduction), 0.0);
    const body::Quat swing = body::rot_x(-g.flexion);
    const body::Vec3 u = swing * u0;
    const body::Vec3 axis = swing * (body::axis_angle(u0, -sign * g.twist) * n0);
    set(a.upper, chest * body::aim(a.upper_dir, a.elbow_axis, u, axis));
    set(a.fore, world[a.upper] * body::axis_angle(a.elbow_axis, g.elbow - a.rest_elbow));
  }

  // Legs: two-bone IK from the hip to the ankle target.
  for (int s = 0; s < 2; ++s) {
    const Leg& l = leg_[s];
    const FootState& f = t.feet[s];
    set(l.hip_joint, root);
    const body::Vec3 hip = hip_position(t, s);
    const body::Vec3 ankle = ankle_target(f, s);
    body::Vec3 d = ankle - hip;
    double dist = d.norm();
    const double max_reach = kMaxReach * (l.l1 + l.l2);
    const double min_reach = std::abs(l.l1 - l.l2) + 1e-3;
    dist = std::clamp(dist, min_reach, max_reach);
    const body::Vec3 dn = d.normalized();
    // The knee bends toward the foot's forward direction.
    const body::Vec3 forward = body::rot_y(f.yaw) * body::Vec3::UnitZ();
    body::Vec3 pole = perpendicular_part(forward, dn);
    if (pole.norm() < 1e-6) pole = perpendicular_part(root * body::Vec3::UnitZ(), dn);
    pole.normalize();
    const double cos_hip = std::clamp((l.l1 * l.l1 + dist * dist - l.l2 * l.l2) / (2 * l.l1 * dist), -1.0, 1.0);
    const double hip_angle = std::acos(cos_hip);
    const body::Vec3 knee = hip + l.l1 * (std::cos(hip_angle) * dn + std::sin(hip_angle) * pole);
    const body::Vec3 end = hip + dist * dn;
    const body::Vec3 rest_forward = body::Vec3::UnitZ();
    set(l.up, body::aim(l.knee_rest - l.hip_rest, rest_forward, knee - hip, pole));
    set(l.knee, body::aim(l.ankle_rest - l.knee_rest, rest_forward, end - knee, pole));
    const body::Quat foot = body::rot_y(f.yaw) * body::rot_x(f.pitch);
    set(l.foot, foot);
    set(l.toe, foot * body::rot_x(-f.toe_bend));
  }

  // Remaining joints (hands, fingers, thumbs) keep their rest relation.
  for (int j = 0; j < n; ++j)
    if (!done[j]) world[j] = world[sk.parents[j]];
  return body::pose_from_world(sk, world, t.pelvis);
}

}  // namespace layers::motion
