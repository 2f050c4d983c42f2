// tiny_scene.h -- what the generator tests of users' own files share:
// configs/data/tiny.yaml cut down to one short, coarse scene of a dress
// under a jacket (tiny_tree), one scene generated into a folder and read
// back, and the measures runs are compared by (garment_motion.h).
#pragma once

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "garment_motion.h"
#include "layers/core/config.h"
#include "layers/data/dataset.h"
#include "layers/generate/generator.h"
#include "layers/generate/generator_config.h"
#include "test_paths.h"

namespace layers::generate {

inline void set_outfits(cfg::Node& tree, const std::string& yaml) { cfg::apply_set(tree, "garments.outfits=" + yaml); }

// configs/data/tiny.yaml cut down to one short, coarse scene of a dress
// under a jacket, on a fixed body shape.
inline cfg::Node tiny_tree(const std::vector<std::string>& extra = {}) {
  cfg::Node tree = cfg::load_file(test::source_dir() + "/configs/data/tiny.yaml");
  std::vector<std::string> sets = {"sequences=1",
                                   "frames=3",
                                   "drape_frames=2",
                                   "body.transition_frames=2",
                                   "garments.fit.edge_length=0.1",
                                   "splits.val=0",
                                   "splits.test=0",
                                   "sim.validation.max_h_penetration=1",
                                   "sim.validation.max_l_penetration=1",
                                   "sim.validation.max_stretch=100",
                                   "sim.validation.max_h_crossing_clear=1"};
  sets.insert(sets.end(), extra.begin(), extra.end());
  for (const std::string& s : sets) cfg::apply_set(tree, s);
  set_outfits(tree, "[{inner: [dress], outer: jacket}]");
  return tree;
}

inline data::SequenceData generate_one(const GeneratorConfig& config, const std::string& out) {
  GenerateOptions options;
  options.out = out;
  options.progress = false;
  const GenerateReport report = generate_dataset(config, cfg::to_yaml(cfg::to_node(config)), options);
  EXPECT_EQ(report.written, 1) << (report.skip_reasons.empty() ? "" : report.skip_reasons[0]);
  return data::Dataset::open(out).read_sequence("seq-000000");
}

using test::garment_speed_mm;
using test::mean_distance_mm;

}  // namespace layers::generate
