// layers/motion/body_sequence.h -- the body part of a LAYERS-H5 sequence:
// per-frame skinned vertices, root translation and rotation, and joint
// transforms, with room made for the cloth under the arms and between the
// thighs (optional), body
// self-intersections detected, small ones resolved
// (the offending arm abducted or swung forward / backward, the legs
// abducted, by the smallest angle that clears the frame, the correction
// spread smoothly over neighbouring frames) and frames that stay
// intersecting handled by a policy.
#pragma once

#include <string>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/body/self_intersection.h"
#include "layers/body/skin_untangle.h"
#include "layers/motion/motion.h"

namespace layers::motion {

struct SequenceOptions {
  body::IntersectionOptions intersection;
  bool resolve = true;               // try to resolve intersecting frames
  double max_arm_correction = 0.9;   // rad an arm may be turned at most
  double max_leg_correction = 0.35;  // rad of extra leg abduction at most (on top of thigh room's)
  // Room for the cloth under the arms (m; 0 = off): frames where an arm
  // comes closer to the torso than this have it abducted, by at most
  // `max_arm_room_turn` rad, before the checks and repairs below. Two
  // layers of cloth on the arm and two on the torso need about 2 cm of
  // contact margins; a mocap arm resting against the side leaves less.
  double arm_room = 0.0;
  double max_arm_room_turn = 0.3;
  // Room for the cloth between the thighs (m; 0 = off), made after the
  // arms': frames where the legs come closer to each other than this
  // (beyond the top 30% of the thigh) have both legs abducted by the same
  // angle, at most `max_thigh_room_turn` rad each. A trouser leg on each
  // thigh puts two layers of cloth and their contact margins there; a
  // mocap subject standing with the thighs together leaves less.
  double thigh_room = 0.0;
  double max_thigh_room_turn = 0.15;
  // Smoothing of the skin where it passes through itself, applied to every
  // written frame after the pose is final (body::SkinUntangler; passes 0 =
  // off). It changes the stored skin, never the joints.
  body::SkinUntangleOptions skin_untangle;
  // What happens to frames still intersecting after resolution:
  // "longest_run" keeps the longest run of consecutive clean frames,
  // "first_run" the frames before the first bad one (a clean window:
  // the motion as asked, cut short),
  // "drop" removes the bad frames (the sequence then skips in time),
  // "keep" keeps them (only reported).
  std::string on_intersection = "longest_run";
};

// What arm or thigh room did: the frames whose limbs it turned, and the
// largest turn (rad, per limb).
struct RoomReport {
  int frames = 0;
  double turn = 0.0;
  // "<limbs> turned in <frames> of <of> frames, by up to <turn> rad": the
  // line `layers body` and the generator's debug log print.
  std::string describe(const std::string& limbs, int of) const;
};

struct IntersectionReport {
  int frames = 0;        // frames of the motion checked
  int intersecting = 0;  // frames that offend before resolution (deeper than the tolerance, or short of the gap)
  int resolved = 0;      // of those, frames clean after resolution
  int remaining = 0;     // frames still offending after resolution: unresolvable within the turn limits
  // The repair's size: frames whose limbs it turned (the spread included),
  // the largest turn of a limb root (rad) and the largest move of a skin
  // vertex (m) against the pose before it (after arm and thigh room).
  int corrected = 0;
  double max_turn = 0.0, max_shift = 0.0;
  int dropped = 0;                               // frames removed by the policy
  double worst_before = 0.0, worst_after = 0.0;  // deepest penetration (m), before and after resolution
  // Exact crossings between body regions (SelfIntersection's `exact`):
  // crossing face pairs summed over the frames, before and after
  // resolution, and for how many limbs the repair aimed at them (4, fewer
  // where aiming at them left frames deep that the depth alone clears).
  long crossing_before = 0, crossing_after = 0;
  int crossing_limbs = 0;
  RoomReport arm_room, thigh_room;
  // Skin untangling (SequenceOptions::skin_untangle), over the written
  // frames: skin faces crossing another skin face, summed before and after,
  // and the frames it changed.
  long skin_crossing_before = 0, skin_crossing_after = 0;
  int skin_frames = 0;
  double share_intersecting() const { return frames ? static_cast<double>(intersecting) / frames : 0.0; }
};

struct BodySequence {
  int num_frames = 0, num_vertices = 0, num_joints = 0;
  std::string motion;             // MotionSource::describe()
  std::vector<float> positions;   // [T, Vb, 3]
  std::vector<float> root;        // [T, 3]  root joint (pelvis) position
  std::vector<float> root_rot;    // [T, 4]  root rotation relative to rest, w x y z
  std::vector<float> joints;      // [T, J, 3, 4]  see joint_matrices()
  std::vector<int> source_frame;  // [T] motion frame each output frame comes from
  IntersectionReport intersection;
};

// Poses, checks and (per options) repairs every frame of `motion`. Throws
// InputError when the policy leaves no frame.
BodySequence generate_body_sequence(const body::Body& body, const MotionSource& motion,
                                    const SequenceOptions& options = {});

// The skin vertices of frame `frame` (num_vertices x 3).
geometry::Points frame_vertices(const BodySequence& sequence, int frame);

}  // namespace layers::motion
