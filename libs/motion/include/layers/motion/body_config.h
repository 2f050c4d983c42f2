// layers/motion/body_config.h -- the typed config of the body-and-motion
// part of a scene (embedded by the generator config, used by the `layers
// body` verb), shape sampling ranges, and a one-call generator.
//
// YAML example:
//   body:
//     shape: {gender: 0.3, muscle: 0.5, weight: 0.6, height: 0.45}
//     motion: procedural:walk      # or bvh:<path>, or a path ending in .bvh
//     frames: 120                  # 0 = the whole BVH clip (+ transition)
//     seed: 7
//     transition_frames: 15        # blend in from the T-pose
//     intersection_tolerance_mm: 4
//     self_gap_mm: 0               # > 0: parts that are not neighbours keep this room (the paper's 4)
//     arm_room_mm: 0               # > 0: abduct arms closer than this to the torso
//     thigh_room_mm: 0             # > 0: abduct legs whose thighs come closer than this
//     skin_untangle: {passes: 0, margin_mm: 0.5, steps: 3}  # push the skin out of itself
//     on_intersection: longest_run # or first_run, drop, keep
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/core/config.h"
#include "layers/motion/body_sequence.h"
#include "layers/motion/motion.h"

namespace layers::motion {

// SequenceOptions::skin_untangle as a config block (body::SkinUntangler).
struct SkinUntangleConfig {
  int passes = 0;
  double margin_mm = 0.5;
  int steps = 3;

  template <class V>
  void visit(V& v) {
    v("passes", passes,
      cfg::opt().range(0, 100).help("rounds of pushing the posed skin out of itself where it crosses (0 = off)"));
    v("margin_mm", margin_mm, cfg::opt().range(0, 10).help("how far past the other sheet a pushed vertex goes"));
    v("steps", steps, cfg::opt().range(0, 20).help("Taubin lambda/mu step pairs after each push"));
  }
  body::SkinUntangleOptions options() const {
    body::SkinUntangleOptions o;
    o.passes = passes;
    o.margin = margin_mm / 1000.0;
    o.steps = steps;
    return o;
  }
};

// The one definition of the body.self_gap_mm setting (motion configs and
// the generator's body sampling).
inline const cfg::Opt kSelfGapOption = cfg::opt().range(0, 50).help(
    "room (mm) body parts that are not neighbours keep from each other; closer frames are repaired or dropped as "
    "unresolvable (0 = off: only depth over the tolerance counts; the paper keeps 4)");

struct BodyMotionConfig {
  body::ShapeParams shape;
  std::string motion = "procedural:walk";
  int frames = 120;
  std::uint64_t seed = 0;
  int transition_frames = 15;
  double intersection_tolerance_mm = 4.0;
  double self_gap_mm = 0.0;    // body::IntersectionOptions::gap; 0 = off
  double arm_room_mm = 0.0;    // SequenceOptions::arm_room; 0 = off
  double thigh_room_mm = 0.0;  // SequenceOptions::thigh_room; 0 = off
  SkinUntangleConfig skin_untangle;
  std::string on_intersection = "longest_run";
  std::string assets;  // asset root; "" = $LAYERS_ASSETS or the build-time default

  template <class V>
  void visit(V& v) {
    v("shape", shape);
    v("motion", motion, cfg::opt().help("procedural:<kind>, bvh:<path> or a .bvh path"));
    v("frames", frames,
      cfg::opt().range(0, 100000).help("total frames at 30 fps, transition included; 0 = whole clip (at most 100000)"));
    v("seed", seed, cfg::opt().help("randomises procedural speed, amplitude and choices"));
    v("transition_frames", transition_frames,
      cfg::opt().range(0, 100000).help("frames blending in from the T-pose (at most 100000)"));
    v("intersection_tolerance_mm", intersection_tolerance_mm,
      cfg::opt().range(0.5, 50).help("allowed self-intersection depth"));
    v("self_gap_mm", self_gap_mm, kSelfGapOption);
    v("arm_room_mm", arm_room_mm,
      cfg::opt().range(0, 100).help("room for the cloth between arms and torso; closer arms are abducted (0 = off)"));
    v("thigh_room_mm", thigh_room_mm,
      cfg::opt().range(0, 100).help("room for the cloth between the thighs; closer legs are abducted (0 = off)"));
    v("skin_untangle", skin_untangle);
    v("on_intersection", on_intersection, cfg::opt().choices({"longest_run", "first_run", "drop", "keep"}));
    v("assets", assets,
      cfg::opt().help("asset root (default: $LAYERS_ASSETS, then <prefix>/share/layers/assets, then <source>/assets)"));
  }
};

// Ranges [lo, hi] within which shapes are drawn per sequence.
struct ShapeSampling {
  std::vector<double> gender{0.0, 1.0};
  std::vector<double> muscle{0.25, 0.75};
  std::vector<double> weight{0.25, 0.75};
  std::vector<double> height{0.3, 0.7};

  template <class V>
  void visit(V& v) {
    v("gender", gender, cfg::opt().range(0, 1).help("[lo, hi]"));
    v("muscle", muscle, cfg::opt().range(0, 1).help("[lo, hi]"));
    v("weight", weight, cfg::opt().range(0, 1).help("[lo, hi]"));
    v("height", height, cfg::opt().range(0, 1).help("[lo, hi] (0.5 = average, 1.67 m)"));
  }
};

// Uniform draws within the ranges; InputError for a range that is not
// two numbers lo <= hi.
body::ShapeParams sample_shape(const ShapeSampling& ranges, std::uint64_t seed);

MotionSpec motion_spec(const BodyMotionConfig& config);
SequenceOptions sequence_options(const BodyMotionConfig& config);

struct GeneratedBody {
  body::Body body;
  BodySequence sequence;
};

// Loads the model (cached), builds the shaped body, the motion and the
// checked per-frame arrays.
GeneratedBody generate_body(const BodyMotionConfig& config);

}  // namespace layers::motion
