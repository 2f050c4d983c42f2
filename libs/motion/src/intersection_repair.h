// intersection_repair.h (private to layers::motion) -- room for the cloth
// under the arms and between the thighs, and repairs of body self-intersections over a pose
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
#include "layers/motion/body_sequence.h"

namespace layers::motion {

struct RepairLimits {
  double arm = 0.9;  // rad
  double leg = 0.35;
  // Per limb (left arm, right arm, left leg, right leg): whether its exact
  // crossings are aimed at (else only its depth is).
  std::array<bool, 4> crossings{true, true, true, true};
};

// Where make_room() makes room: under the arms (FrameIntersection::arm_gap,
// each arm abducted about the chest) or between the thighs (thigh_gap, both
// legs abducted about the pelvis by the same angle).
enum class Room { arms, legs };

// In the frames where a limb comes closer to its neighbour than `room` (m;
// the gap named above), abducts it by the smallest angle (0.05 rad steps,
// at most `limit`) that gives that room, or by the angle that gives the
// most room when none does. Never by more than the frame's harmless
// angle: in some poses abduction brings the limb nearer (an arm swung
// forward and in, a leg crossed in front of the other), and no frame's
// limb (those the spread reaches included) is taken more than 2 mm closer
// than min(its gap, room). The per-frame angles are spread over
// neighbouring frames with smooth envelopes (above the needs, below the
// harmless angles). Returns the frames turned and the largest angle
// applied; nothing is turned when `room` is 0.
RoomReport make_room(const body::Body& body, const body::SelfIntersection& checker, Room where, double room,
                     double limit, std::vector<body::Pose>& poses);

// `found` holds the check of every pose and is updated with the result,
// counting only the crossings of the limbs `limits.crossings` aims at.
void repair_intersections(const body::Body& body, const body::SelfIntersection& checker, const RepairLimits& limits,
                          std::vector<body::Pose>& poses, std::vector<body::FrameIntersection>& found);

}  // namespace layers::motion
