// intersection_repair.h (private to layers::motion) -- room for the cloth
// under the arms, and repairs of body self-intersections over a pose
// sequence: the offending arm is abducted
// or swung forward / backward (one way per run of affected frames: the
// way that alone clears most of them), the legs abducted, each by the smallest
// angle (in 0.05 rad steps) that clears a frame; the per-frame angles are
// spread over neighbouring frames with a smooth envelope that stays above
// them, applied to the original poses, and the search repeats for frames
// that still fail.
#pragma once

#include <array>
#include <vector>

#include "layers/body/self_intersection.h"

namespace layers::motion {

struct RepairLimits {
  double arm = 0.9;  // rad
  double leg = 0.35;
  // Per limb (left arm, right arm, left leg, right leg): whether its exact
  // crossings are aimed at (else only its depth is).
  std::array<bool, 4> crossings{true, true, true, true};
};

// Arm room: in the frames where an arm comes closer to the torso than
// `room` (m; FrameIntersection::arm_gap), abducts it by the smallest angle
// (0.05 rad steps, at most `limit`) that gives it that room, or by the
// angle that gives the most room when none does. Never by more than the
// frame's harmless angle: in some poses abduction brings the arm nearer
// the torso, and no frame's arm (those the spread reaches included) is
// taken more than 2 mm closer than min(its gap, room). The per-frame
// angles are spread over neighbouring frames with smooth envelopes (above
// the needs, below the harmless angles). Returns the largest angle applied (rad) and counts the frames
// turned in `frames`.
double make_arm_room(const body::Body& body, const body::SelfIntersection& checker, double room, double limit,
                     std::vector<body::Pose>& poses, int& frames);

// `found` holds the check of every pose and is updated with the result,
// counting only the crossings of the limbs `limits.crossings` aims at.
void repair_intersections(const body::Body& body, const body::SelfIntersection& checker, const RepairLimits& limits,
                          std::vector<body::Pose>& poses, std::vector<body::FrameIntersection>& found);

}  // namespace layers::motion
