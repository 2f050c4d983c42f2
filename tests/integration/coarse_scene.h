// tests/integration/coarse_scene.h -- the command-line settings of the
// own-garment CLI tests: configs/data/tiny.yaml cut to one short, coarse
// scene (validation limits opened: these tests are about the pipeline),
// with `outfit` (YAML) as its outfits.
#pragma once

#include <string>

#include "test_paths.h"

namespace layers::test {

inline std::string coarse_scene_settings(const std::string& outfit) {
  return " --config " + source_dir() +
         "/configs/data/tiny.yaml --set frames=3 --set drape_frames=2 --set body.transition_frames=2"
         " --set garments.fit.edge_length=0.1 --set sim.validation.max_l_penetration=1"
         " --set sim.validation.max_h_penetration=1 --set sim.validation.max_stretch=100"
         " --set sim.validation.max_h_crossing_clear=1 --set 'garments.outfits=" +
         outfit + "'";
}

}  // namespace layers::test
