// pose_solver.h (private to layers::motion) -- turns high-level targets
// (pelvis placement, spine and head angles, arm angles, foot placements)
// into a Pose of the cmu_mb skeleton: the legs by analytic two-bone IK
// with the knee hinged toward the foot's forward direction, the arms by
// aiming the upper arm and hinging the elbow, the feet and toes directly.
// Used by the procedural motions.
#pragma once

#include <array>

#include "layers/body/body_model.h"

namespace layers::motion {

// Arm angles in the chest frame (radians). abduction: away from the body
// in the frontal plane (0 = hanging); flexion: forward swing of the
// abducted arm (negative = backward); twist: external rotation of the
// upper arm; elbow: angle between upper arm and forearm (0 = straight).
struct ArmAngles {
  double abduction = 0.3;
  double flexion = 0.0;
  double twist = 0.0;
  double elbow = 0.3;
  double clavicle = 0.0;  // shrug (raises the shoulder)
};

// One foot: its ball (the pivot under the toe joint, on the sole) in world
// coordinates, heading and pitch (positive = heel raised), toe bend.
struct FootState {
  body::Vec3 ball = body::Vec3::Zero();
  double yaw = 0.0;
  double pitch = 0.0;
  double toe_bend = 0.0;
  bool planted = true;  // on the ground or landing (the pelvis guard only protects these feet)
};

struct PoseTargets {
  body::Vec3 pelvis = body::Vec3::Zero();                        // world position of the root joint
  double yaw = 0.0, pitch = 0.0, roll = 0.0;                     // pelvis heading, forward tilt, side tilt
  double spine_flex = 0.0, spine_twist = 0.0, spine_bend = 0.0;  // totals over the three spine joints
  double head_pitch = 0.0, head_yaw = 0.0;
  std::array<ArmAngles, 2> arms;  // left, right
  std::array<FootState, 2> feet;  // left, right
};

class PoseSolver {
 public:
  explicit PoseSolver(const body::Body& body);

  body::Pose solve(const PoseTargets& targets) const;

  // How far (m) the pelvis must drop so that the ankles of planted feet
  // are within `reach` (share of the full leg length) of their hips.
  double pelvis_drop_needed(const PoseTargets& targets, double reach) const;

  // Rest-pose quantities the motions are built from.
  double leg_length() const { return leg_[0].l1 + leg_[0].l2; }
  double rest_pelvis_height() const { return pelvis_rest_.y(); }
  double ankle_height() const { return leg_[0].ankle_rest.y(); }
  // Ball position relative to the pelvis in the rest pose (side 0 = left).
  body::Vec3 ball_offset(int side) const { return leg_[side].ball_rest - pelvis_rest_; }
  body::Vec3 hip_offset(int side) const { return leg_[side].hip_rest - pelvis_rest_; }
  // Pelvis height at which an ankle right below the hip, `lateral` m to
  // the side, is at `reach` of the full leg length.
  double standing_pelvis_height(double reach, double lateral) const;

 private:
  struct Leg {
    int hip_joint, up, knee, foot, toe;
    double l1, l2;
    body::Vec3 hip_rest, knee_rest, ankle_rest, ball_rest;
  };
  struct Arm {
    int clavicle, upper, fore;
    body::Vec3 upper_dir, elbow_axis;  // rest
    double rest_elbow;                 // rest angle between upper arm and forearm
  };
  const body::Body& body_;
  std::array<Leg, 2> leg_;
  std::array<Arm, 2> arm_;
  body::Vec3 pelvis_rest_;
  int spine_[3], neck_[3], chest_;

  body::Vec3 hip_position(const PoseTargets& t, int side) const;
  body::Vec3 ankle_target(const FootState& f, int side) const;
};

}  // namespace layers::motion
