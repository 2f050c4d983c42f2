// layers/generate/simulate.h -- one scene from spec to LAYERS-H5 sequence:
// body and motion, garments fitted in the T-pose, drape (warm-up) in the
// T-pose, blend into the motion, record frame by frame with the cloth
// solver, validate.
#pragma once

#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"

namespace layers::generate {

struct SceneResult {
  bool ok = false;
  data::SequenceData sequence;           // when ok
  std::vector<std::string> violations;   // why it was skipped, when not ok
  double mean_h_penetration = 0, mean_l_penetration = 0, max_stretch = 0;
  int simulated_frames = 0;              // warm-up included
  double seconds = 0;
};

// Never writes anything; a scene over its thresholds comes back with
// ok = false and the reasons.
SceneResult simulate_scene(const GeneratorConfig& config, const SceneSpec& spec);

}  // namespace layers::generate
