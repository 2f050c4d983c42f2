// resimulate.cpp -- a stored scene simulated again from the dataset's
// recorded generator config (see resimulate.h).
#include "layers/generate/resimulate.h"

#include <chrono>
#include <cstdio>
#include <filesystem>

#include "layers/core/error.h"
#include "layers/data/manifest.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/imported_garment.h"
#include "layers/generate/own_body.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"

namespace layers::generate {
namespace {

// The manifest's path and the generator config it records; InputError
// (one line) without either, or for frames outside 2..its recorded count.
GeneratorConfig recorded_config(const std::string& dataset_dir, std::int64_t frames, std::string& path) {
  path = (std::filesystem::path(dataset_dir) / "dataset.yaml").string();
  if (!std::filesystem::exists(path))
    throw InputError::message(path, "",
                              "not found: a finished dataset's manifest carries the generator config (generator.yaml) "
                              "the scene is simulated again from");
  const data::DatasetManifest manifest = data::read_manifest(path);
  const std::optional<GeneratorConfig> recorded = recorded_generator_config(manifest.generator_yaml, path);
  if (!recorded)
    throw InputError(path, "generator", "the generator config the dataset was made with",
                     "none (a dataset not made by `layers generate`)");
  if (frames < 2 || frames > recorded->frames)
    throw InputError(path, "frames", "2.." + std::to_string(recorded->frames), std::to_string(frames));
  if (!recorded->garments.files.empty()) {
    // A user's garment files: the same contents as when the dataset was made.
    GeneratorConfig now = *recorded;
    resolve_garment_files(now);
    if (now.garments.files != recorded->garments.files)
      throw InputError(path, "generator.garments.files", "the garment files the dataset was made with",
                       "files whose contents changed since");
  }
  if (recorded->body.own) {
    // A user's body: the same files.
    GeneratorConfig now = *recorded;
    resolve_own_body(now);
    if (now.body.own->hash != recorded->body.own->hash)
      throw InputError(path, "generator.body.own", "the body files the dataset was made with",
                       "files whose contents changed since");
  }
  return *recorded;
}

// The fit's edge length times `edge_scale`; InputError outside the fit's range.
double scaled_edge(const GeneratorConfig& config, double edge_scale, const std::string& path) {
  const double edge = config.garments.fit.edge_length * edge_scale;
  if (!(edge >= 0.004 && edge <= 0.1)) {
    char field[96], got[32];
    std::snprintf(field, sizeof field, "garments.fit.edge_length x %g", edge_scale);
    std::snprintf(got, sizeof got, "%g m", edge);
    throw InputError(path, field, "0.004..0.1 m", got);
  }
  return edge;
}

}  // namespace

void check_resimulation(const std::string& dataset_dir, std::int64_t frames, double edge_scale) {
  std::string path;
  scaled_edge(recorded_config(dataset_dir, frames, path), edge_scale, path);
}

Resimulation resimulate(const std::string& dataset_dir, const std::string& sequence_id, std::int64_t frames,
                        const ResimulateOptions& options) {
  std::string path;
  GeneratorConfig config = recorded_config(dataset_dir, frames, path);
  int index = -1;
  char tail = 0;
  if (std::sscanf(sequence_id.c_str(), "seq-%d%c", &index, &tail) != 1 || index < 0 || scene_id(index) != sequence_id)
    throw InputError(path, "sequence", "an id the generator made (seq-NNNNNN)", "'" + sequence_id + "'");
  // The scene is sampled with the recorded config (same outfit, body,
  // motion and wind); only the fit's resolution changes.
  const SceneSpec spec = sample_scene(config, index);
  config.garments.fit.edge_length = scaled_edge(config, options.edge_scale, path);
  SceneSimulation scene(config, spec);
  if (!scene.usable()) throw InputError::message(path, sequence_id, "cannot be simulated again: " + scene.problem());
  if (frames > scene.recorded_frames())
    throw InputError(path, "frames",
                     "at most " + std::to_string(scene.recorded_frames()) + " for " + sequence_id +
                         " (its body crosses itself beyond repair after that)",
                     std::to_string(frames));
  scene.warm_up();
  Resimulation run;
  const sim::Solver& solver = scene.solver();
  if (options.keep_positions) run.garments.resize(static_cast<std::size_t>(solver.num_cloths()));
  double cpu = 0, wall = 0;
  for (int r = 0; r < frames; ++r) {
    const double start = thread_cpu_seconds();
    const auto wall_start = std::chrono::steady_clock::now();
    scene.record(r);
    if (r > 0) {  // frames 1..n-1, as Blender's steps
      cpu += thread_cpu_seconds() - start;
      wall += std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
    }
    if (!options.keep_positions) continue;
    for (int k = 0; k < solver.num_cloths(); ++k) {
      const geometry::Points p = solver.cloth(k).positions();
      run.garments[static_cast<std::size_t>(k)].insert(run.garments[k].end(), p.data(), p.data() + p.size());
    }
  }
  for (int k = 0; k < solver.num_cloths(); ++k) run.garment_vertices += solver.cloth(k).positions().rows();
  run.cpu_ms_per_frame = 1e3 * cpu / static_cast<double>(frames - 1);
  run.wall_ms_per_frame = 1e3 * wall / static_cast<double>(frames - 1);
  return run;
}

}  // namespace layers::generate
