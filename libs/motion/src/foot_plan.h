// foot_plan.h (private to layers::motion) -- footstep plans for the
// procedural motions: per foot a list of stance intervals (where the ball
// of the foot is planted, with which heading), and the smooth foot
// trajectory between them (C1: quintic blend of position and heading, a
// lift bump with zero end velocities, heel-off before toe-off).
#pragma once

#include <functional>
#include <vector>

#include "pose_solver.h"

namespace layers::motion {

struct Stance {
  double start = 0.0, end = 0.0;         // seconds
  body::Vec3 ball = body::Vec3::Zero();  // planted ball of the foot (y = ground height)
  double yaw = 0.0;
  double min_lift = 0.0;  // the swing into this stance lifts at least this share of a full step
};

struct SwingStyle {
  double clearance = 0.06;   // peak lift of a full step (m)
  double heel_off = 0.35;    // heel-raise angle at toe-off for a full step (rad)
  double heel_share = 0.35;  // last share of the stance during which the heel rises ...
  double heel_time = 0.25;   // ... but at most this long (s)
  double full_step = 0.25;   // step length (m) that gets the full lift and heel-off
};

// The foot at time t.
FootState foot_at(const std::vector<Stance>& plan, double t, const SwingStyle& style);

// Steps along a pelvis path: stance k of this foot spans
// [(k + phase) T, (k + phase + duty) T]; its ball is planted at the path
// position at mid-stance plus `offset` (in the path's heading frame), with
// the path heading plus `toe_out`. Covers [0, duration].
std::vector<Stance> plan_steps(const std::function<body::Vec3(double)>& position,
                               const std::function<double(double)>& yaw, double period, double duty, double phase,
                               double duration, const body::Vec3& offset, double toe_out);

// A C1 bump on [0, 1]: 0 at both ends with zero slope, 1 at 0.5.
double bump(double s);

}  // namespace layers::motion
