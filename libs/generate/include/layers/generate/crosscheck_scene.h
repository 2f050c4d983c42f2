// layers/generate/crosscheck_scene.h -- the files exchanged with Blender's
// cloth solver for `layers crosscheck`: the scene folder handed to
// scripts/blender/crosscheck_sim.py (a `layers export --format pc2` of the
// sequence, each garment's rest shape as <seq>_<mesh>_rest.obj and
// crosscheck.json: mesh names, layers, attributes, self-collision and the
// per-frame wind) and the results read back (<mesh>.pc2 per garment,
// timing.txt).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/generate/crosscheck.h"

namespace layers::data {
class Dataset;
}

namespace layers::generate {

struct CrosscheckScene {
  std::string folder;               // the export folder
  std::string manifest;             // <folder>/crosscheck.json
  std::string prefix;               // file prefix of every mesh, "<seq>_"
  std::vector<std::string> meshes;  // garment mesh names, in sequence order
  std::int64_t frames = 0;
};

// crosscheck.json for garments `garments` named `meshes` (same order) and
// frames [0, frames) of `wind`.
std::string crosscheck_manifest(const std::string& prefix, const std::vector<std::string>& meshes,
                                const std::vector<data::GarmentStatic>& garments, const data::WindData& wind,
                                std::int64_t frames);

// Exports frames [0, frames) of sequence `id` into `folder` (created) with
// the rest shapes and crosscheck.json.
CrosscheckScene write_crosscheck_scene(const data::Dataset& dataset, const std::string& id, std::int64_t frames,
                                       const std::string& folder);

// The run Blender wrote into `dir`: <dir>/<mesh>.pc2 for every garment of
// `scene` (vertex counts as in `seq`, at least scene.frames samples) and
// the ms_per_frame line of <dir>/timing.txt. InputError naming the file
// otherwise.
CrosscheckRun read_crosscheck_run(const std::string& label, const std::string& dir, const CrosscheckScene& scene,
                                  const data::SequenceData& seq);

}  // namespace layers::generate
