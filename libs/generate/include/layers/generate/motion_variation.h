// layers/generate/motion_variation.h -- parametric motion families: the
// optional `body.variation` section of a generator config and the per-scene
// draw that turns a `body.motions` entry into one exact motion.
//
//   body:
//     variation:
//       speed: [0.8, 1.25]        # tempo multiplier
//       amplitude: [0.75, 1.25]   # size multiplier (arm swing, jump height, squat depth)
//       phase: [0, 1]             # cycle offset (share of a cycle) / start delay
//       step_length: [0.85, 1.2]  # stride, jump distance, step-down reach (x nominal)
//       turn_angle: [90, 180]     # degrees per turn (turn)
//       spin_rate: [90, 240]      # degrees per second (spin)
//       clip_window: random       # BVH clips: start (frame 0) or a random window
//       mirror: 0.5               # BVH clips: probability of the left-right mirror
//
// Without the section every scene plays its entry as before (procedural
// kinds draw speed and amplitude from the scene seed), so old configs
// give the same bytes.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/core/config.h"

namespace layers::generate {

struct MotionVariation {
  std::vector<double> speed{0.8, 1.25};
  std::vector<double> amplitude{0.75, 1.25};
  std::vector<double> phase{0.0, 1.0};
  std::vector<double> step_length{0.85, 1.2};
  std::vector<double> turn_angle{90, 180};
  std::vector<double> spin_rate{90, 240};
  std::string clip_window = "start";
  double mirror = 0.0;

  template <class V>
  void visit(V& v) {
    v("speed", speed, cfg::opt().range(0.3, 2.5).help("[lo, hi] tempo multiplier (1 = nominal)"));
    v("amplitude", amplitude, cfg::opt().range(0.1, 2.5).help("[lo, hi] size multiplier"));
    v("phase", phase, cfg::opt().range(0, 1).help("[lo, hi] cycle offset / start delay, share of a cycle"));
    v("step_length", step_length,
      cfg::opt().range(0.3, 2.5).help("[lo, hi] stride, jump distance, step-down reach, x nominal"));
    v("turn_angle", turn_angle, cfg::opt().range(1, 720).help("[lo, hi] degrees per turn (procedural:turn)"));
    v("spin_rate", spin_rate, cfg::opt().range(1, 720).help("[lo, hi] degrees per second (procedural:spin)"));
    v("clip_window", clip_window,
      cfg::opt().choices({"start", "random"}).help("BVH clips: from frame 0, or a window drawn per scene"));
    v("mirror", mirror, cfg::opt().range(0, 1).help("BVH clips: probability of the left-right mirror"));
  }
};

// Ranges are [lo, hi] pairs with lo <= hi: InputError naming `file` and
// `path`.<field> otherwise.
void check(const MotionVariation& variation, const std::string& file, const std::string& path);

// The exact motion spec of one scene: `entry` (a body.motions entry) with
// its parameters drawn from `variation`, e.g. "procedural:hop speed=1.412
// amplitude=0.958 phase=0.613 step=1.046 variant=forward seed=..." or
// "cmu/131_01_start_walk_stop.bvh window=37+90 mirror=1". `frames` is the
// motion's length without the transition (a clip window's length).
// Procedural parameters are drawn from `seed` (the scene's seed, which the
// description carries). Clip windows are drawn without replacement: the
// scene that is the `occurrence`-th (0-based) of its dataset to play this
// clip takes the next window of a permutation of the clip's windows seeded
// by `dataset_seed` (one for mirrored, one for plain scenes), so windows
// repeat only once a clip has played all of them. An entry that already
// carries parameters is returned as it is. InputError when a clip is
// shorter than `frames` or its file is missing.
std::string vary_motion(const MotionVariation& variation, const std::string& entry, int frames, std::uint64_t seed,
                        int occurrence = 0, std::uint64_t dataset_seed = 0, const std::string& asset_root = "");

// The family of a motion description: its first word ("procedural:walk",
// "bvh:cmu/131_01_start_walk_stop.bvh", or an own body's "animation" or
// "animation:<file>#<name>");
// a clip entry without "bvh:" gets it.
std::string motion_family(const std::string& motion);

}  // namespace layers::generate
