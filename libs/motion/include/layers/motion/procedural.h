// layers/motion/procedural.h -- parameterised procedural motions, so that
// datasets are not limited to the shipped clips.
//
// Kinds: walk, run, turn (in place, by 90-180 degrees, repeatedly), spin
// (continuous turning on the spot), jump (in place or forward), hop (quick
// small repeated jumps, in place or forward), step_down (off a 12-25 cm
// ledge), arm_raise (side or front, one arm, both or alternating), wave,
// squat. Every motion starts at rest (zero velocity,
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

// A motion of a parametric family. The fields after `seed` default to
// "the kind decides from the seed" (today's motions); set, they pin the
// motion down (variation.h draws them per scene) and describe() lists them.
struct ProceduralParams {
  std::string kind = "walk";
  int frames = 150;              // at 30 fps
  double speed = 1.0;            // tempo multiplier (1 = nominal, e.g. 1.2 m/s walk for a 1.67 m body)
  double amplitude = 1.0;        // size multiplier (arm swing, jump height, squat depth, ...)
  std::uint64_t seed = 0;        // kind-specific choices left to chance: curvature, small offsets
  double phase = 0.0;            // share of a cycle the periodic motion is shifted by (start offset), [0, 1]
  double step_length = 1.0;      // stride (walk, run), jump/hop distance, step_down reach: x nominal
  double turn_angle = 0.0;       // turn: degrees per turn; spin: degrees per second; 0 = from the seed
  int direction = 0;             // turn, spin: +1 left (counter-clockwise from above), -1 right, 0 = from the seed
  int variant = -1;              // index into procedural_variants(kind); -1 = from the seed
  bool explicit_params = false;  // describe() lists every parameter (set by parse and variation draws)
};

// The discrete choices of a kind (e.g. arm_raise: "front-both", ...,
// "side-alternate"; wave: "left", "right"); empty for kinds without any.
const std::vector<std::string>& procedural_variants(const std::string& kind);

// Draws speed in [0.8, 1.25] and amplitude in [0.75, 1.25] from `seed`.
ProceduralParams sample_procedural(const std::string& kind, int frames, std::uint64_t seed);

// "procedural:<kind>" for plain params; with explicit_params the full,
// replayable form, e.g. "procedural:walk speed=1.134 amplitude=0.912
// phase=0.250 step=1.050 seed=7d1f..." (only the parameters the kind uses).
std::string describe_procedural(const ProceduralParams& params);

// Reads the form describe_procedural() writes (the text after
// "procedural:"): a kind, then optional key=value tokens (speed,
// amplitude, phase, step, turn, dir=left|right, variant=<name>, seed=<hex>).
// Without tokens it is sample_procedural(kind, frames, seed). InputError
// naming `field` for unknown keys or bad values.
ProceduralParams parse_procedural(const std::string& text, int frames, std::uint64_t seed, const std::string& field);

// Throws InputError (field "motion") for an unknown kind.
std::unique_ptr<PoseTrack> make_procedural(const ProceduralParams& params, const body::Body& body);

}  // namespace layers::motion
