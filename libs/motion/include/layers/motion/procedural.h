// layers/motion/procedural.h -- parameterised procedural motions, so that
// datasets are not limited to the shipped clips.
//
// Kinds: walk, run, turn (in place, by 90-180 degrees, repeatedly), spin
// (continuous turning on the spot), jump (in place or forward), step_down
// (off a 12-25 cm ledge), arm_raise (side or front, one arm, both or
// alternating), wave, squat. Every motion starts at rest (zero velocity,
// so a T-pose transition joins it smoothly) and is C1 in time: foot
// trajectories use quintic blends and zero-slope lift bumps, the pelvis and
// upper body follow smooth periodic curves with smooth envelopes. Feet are
// planted by leg IK (no sliding, soles on the ground in stance); arms stay
// abducted enough to clear the torso for the body's weight and muscle.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "layers/motion/motion.h"

namespace layers::motion {

const std::vector<std::string>& procedural_kinds();

struct ProceduralParams {
  std::string kind = "walk";
  int frames = 150;        // at 30 fps
  double speed = 1.0;      // tempo multiplier (1 = nominal, e.g. 1.2 m/s walk for a 1.67 m body)
  double amplitude = 1.0;  // size multiplier (arm swing, jump height, squat depth, ...)
  std::uint64_t seed = 0;  // kind-specific choices: direction, side, variant, path curvature
};

// Draws speed in [0.8, 1.25] and amplitude in [0.75, 1.25] from `seed`.
ProceduralParams sample_procedural(const std::string& kind, int frames, std::uint64_t seed);

// Throws InputError (field "motion") for an unknown kind.
std::unique_ptr<PoseTrack> make_procedural(const ProceduralParams& params, const body::Body& body);

}  // namespace layers::motion
