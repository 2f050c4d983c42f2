// crosscheck_ours.cpp -- our side of `layers crosscheck`'s timing: the
// stored sequence's scene simulated again from the generator config in the
// dataset's manifest and timed frame by frame on one thread (see
// crosscheck.h).
#include <cstdio>
#include <filesystem>

#include "layers/core/error.h"
#include "layers/data/manifest.h"
#include "layers/generate/crosscheck.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"

namespace layers::generate {

CrosscheckRun resimulate_ours(const std::string& dataset_dir, const std::string& sequence_id, std::int64_t frames) {
  // The config the dataset was made with, as its manifest records it.
  const std::string path = (std::filesystem::path(dataset_dir) / "dataset.yaml").string();
  if (!std::filesystem::exists(path))
    throw InputError::message(path, "",
                              "not found: a finished dataset's manifest carries the generator config (generator.yaml) "
                              "the scene is simulated again from");
  const data::DatasetManifest manifest = data::read_manifest(path);
  const std::optional<GeneratorConfig> recorded = recorded_generator_config(manifest.generator_yaml, path);
  if (!recorded)
    throw InputError(path, "generator", "the generator config the dataset was made with",
                     "none (a dataset not made by `layers generate`)");
  const GeneratorConfig& config = *recorded;
  int index = -1;
  char tail = 0;
  if (std::sscanf(sequence_id.c_str(), "seq-%d%c", &index, &tail) != 1 || index < 0 || scene_id(index) != sequence_id)
    throw InputError(path, "sequence", "an id the generator made (seq-NNNNNN)", "'" + sequence_id + "'");
  if (frames < 2 || frames > config.frames)
    throw InputError(path, "frames", "2.." + std::to_string(config.frames), std::to_string(frames));
  SceneSimulation scene(config, sample_scene(config, index));
  if (!scene.usable()) throw InputError::message(path, sequence_id, "cannot be simulated again: " + scene.problem());
  scene.warm_up();
  CrosscheckRun run;
  run.label = kOursAgain;
  const sim::Solver& solver = scene.solver();
  run.garments.resize(static_cast<std::size_t>(solver.num_cloths()));
  double cpu = 0;
  for (int r = 0; r < frames; ++r) {
    const double start = thread_cpu_seconds();
    scene.record(r);
    if (r > 0) cpu += thread_cpu_seconds() - start;  // frames 1..n-1, as Blender's steps
    for (int k = 0; k < solver.num_cloths(); ++k) {
      const geometry::Points& p = solver.cloth(k).positions();
      run.garments[k].insert(run.garments[k].end(), p.data(), p.data() + p.size());
    }
  }
  run.ms_per_frame = 1e3 * cpu / static_cast<double>(frames - 1);
  return run;
}

}  // namespace layers::generate
