// layers/generate/crosscheck_scene.h -- the files exchanged with Blender's
// cloth solver for `layers crosscheck`: the scene folder handed to
// scripts/blender/crosscheck_sim.py (a `layers export --format pc2` of the
// sequence, each garment's rest shape as <seq>_<mesh>_rest.obj and
// crosscheck.json: mesh names, layers, attributes, self-collision and the
// per-frame wind, and the gaps our solver keeps) and the results read back (<mesh>.pc2 per garment,
// timing.txt).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/generate/crosscheck.h"

namespace layers::data {
class Dataset;
struct DatasetManifest;
}  // namespace layers::data

namespace layers::generate {

struct CrosscheckScene {
  std::string folder;               // the export folder
  std::string manifest;             // <folder>/crosscheck.json
  std::string prefix;               // file prefix of every mesh, "<seq>_"
  std::vector<std::string> meshes;  // garment mesh names, in sequence order
  std::int64_t frames = 0;
};

// The gaps our solver keeps (m): garment-body, inner-outer garment, and
// within one garment (sim::SolverConfig body_thickness, layer_thickness,
// self_thickness). The Blender script maps them to its distances so that
// Blender's effective gaps equal these.
struct CrosscheckGaps {
  double body = 0, layer = 0, self = 0;
  bool recorded = false;  // from the dataset's generator config (else the solver's defaults)
};
// The gaps of the generator config the manifest records, else the solver's
// defaults (recorded = false).
CrosscheckGaps crosscheck_gaps(const data::DatasetManifest& manifest, const std::string& file);

// crosscheck.json for garments `garments` named `meshes` (same order),
// frames [0, frames) of `wind` and `gaps`.
std::string crosscheck_manifest(const std::string& prefix, const std::vector<std::string>& meshes,
                                const std::vector<data::GarmentStatic>& garments, const data::WindData& wind,
                                std::int64_t frames, const CrosscheckGaps& gaps);

// Exports frames [0, frames) of sequence `id` into `folder` (created) with
// the rest shapes and crosscheck.json (with crosscheck_gaps of the
// dataset's manifest).
CrosscheckScene write_crosscheck_scene(const data::Dataset& dataset, const std::string& id, std::int64_t frames,
                                       const std::string& folder);

// The run Blender wrote into `dir`: <dir>/<mesh>.pc2 for every garment of
// `scene` (vertex counts as in `seq`, at least scene.frames samples) and
// the ms_per_frame line of <dir>/timing.txt. InputError naming the file
// otherwise.
CrosscheckRun read_crosscheck_run(const std::string& label, const std::string& dir, const CrosscheckScene& scene,
                                  const data::SequenceData& seq);

}  // namespace layers::generate
