// The Blender scene folder of `layers crosscheck` and its results (see
// crosscheck_scene.h).
#include "layers/generate/crosscheck_scene.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/core/error.h"
#include "layers/data/dataset.h"
#include "layers/data/export.h"
#include "layers/data/manifest.h"
#include "layers/data/obj.h"
#include "layers/data/pc2.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/simulate.h"

namespace layers::generate {

namespace {

namespace fs = std::filesystem;

std::string json_string(const std::string& text) {
  std::string out = "\"";
  for (char c : text) {
    if (c == '"' || c == '\\') out += '\\';
    if (static_cast<unsigned char>(c) < 0x20) continue;
    out += c;
  }
  return out + "\"";
}

std::string json_number(double v) {
  if (!std::isfinite(v)) return "0";
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", v);
  return buf;
}

std::string json_numbers(const std::vector<float>& values, std::size_t count) {
  std::string out = "[";
  for (std::size_t i = 0; i < count && i < values.size(); ++i) out += (i ? "," : "") + json_number(values[i]);
  return out + "]";
}

}  // namespace

CrosscheckGaps crosscheck_gaps(const data::DatasetManifest& manifest, const std::string& file) {
  const std::optional<GeneratorConfig> recorded = recorded_generator_config(manifest.generator_yaml, file);
  const sim::SolverConfig solver = recorded ? recorded->sim : sim::SolverConfig();
  CrosscheckGaps gaps;
  gaps.recorded = recorded.has_value();
  gaps.body = solver.body_thickness;
  gaps.layer = solver.layer_thickness;
  gaps.self = solver.self_thickness;
  return gaps;
}

std::string crosscheck_manifest(const std::string& prefix, const std::vector<std::string>& meshes,
                                const std::vector<data::GarmentStatic>& garments, const data::WindData& wind,
                                std::int64_t frames, const CrosscheckGaps& gaps) {
  if (meshes.size() != garments.size())
    throw Error("crosscheck_manifest: " + std::to_string(meshes.size()) + " mesh names for " +
                std::to_string(garments.size()) + " garments");
  std::ostringstream out;
  out << "{\n  \"format\": \"layers-crosscheck\",\n  \"prefix\": " << json_string(prefix)
      << ",\n  \"frames\": " << frames << ",\n  \"garments\": [";
  for (std::size_t k = 0; k < garments.size(); ++k) {
    const data::GarmentStatic& g = garments[k];
    out << (k ? ",\n" : "\n") << "    {\"mesh\": " << json_string(meshes[k]) << ", \"type\": " << json_string(g.type)
        << ", \"layer\": " << g.layer << ", \"self_collision\": " << (garment_self_contact(g) ? "true" : "false")
        << ", \"attributes\": {";
    bool first = true;
    for (const auto& [key, value] : g.attributes) {
      out << (first ? "" : ", ") << json_string(key) << ": " << json_number(value);
      first = false;
    }
    out << "}}";
  }
  const auto n = static_cast<std::size_t>(frames);
  out << "\n  ],\n  \"wind\": {\"rotation\": " << json_numbers(wind.rotation, 4 * n)
      << ", \"strength\": " << json_numbers(wind.strength, n) << "},\n  \"gaps\": {\"body\": " << json_number(gaps.body)
      << ", \"layer\": " << json_number(gaps.layer) << ", \"self\": " << json_number(gaps.self) << "}\n}\n";
  return out.str();
}

CrosscheckScene write_crosscheck_scene(const data::Dataset& dataset, const std::string& id, std::int64_t frames,
                                       const std::string& folder) {
  const std::vector<std::string> written =
      data::export_sequence(dataset, id, data::ExportFormat::Pc2, 0, frames, folder);
  const auto statics = dataset.statics(id);
  // export_sequence writes the frame-0 OBJ of every mesh first, the body
  // then each garment: their names give the prefix and the mesh names.
  CrosscheckScene scene;
  scene.folder = folder;
  scene.frames = frames;
  const std::size_t n_meshes = 1 + statics->garments.size();
  if (written.size() < n_meshes) throw Error("crosscheck: export wrote " + std::to_string(written.size()) + " files");
  const std::string body = fs::path(written[0]).filename().string();
  const std::string body_suffix = "body.obj";
  if (body.size() < body_suffix.size() ||
      body.compare(body.size() - body_suffix.size(), body_suffix.size(), body_suffix))
    throw Error("crosscheck: unexpected export file " + written[0]);
  scene.prefix = body.substr(0, body.size() - body_suffix.size());
  for (std::size_t k = 0; k < statics->garments.size(); ++k) {
    const std::string file = fs::path(written[k + 1]).filename().string();
    const std::string mesh = file.substr(scene.prefix.size(), file.size() - scene.prefix.size() - 4);
    scene.meshes.push_back(mesh);
    const data::GarmentStatic& g = statics->garments[k];
    data::write_obj((fs::path(folder) / (scene.prefix + mesh + "_rest.obj")).string(), g.rest, g.faces);
  }
  const data::Window w = dataset.read_frames(id, 0, frames);
  scene.manifest = (fs::path(folder) / "crosscheck.json").string();
  const CrosscheckGaps gaps = crosscheck_gaps(dataset.manifest(), dataset.path());
  std::ofstream(scene.manifest) << crosscheck_manifest(scene.prefix, scene.meshes, statics->garments, w.wind, frames,
                                                       gaps);
  return scene;
}

CrosscheckRun read_crosscheck_run(const std::string& label, const std::string& dir, const CrosscheckScene& scene,
                                  const data::SequenceData& seq) {
  CrosscheckRun run;
  run.label = label;
  for (std::size_t k = 0; k < scene.meshes.size(); ++k) {
    const std::string path = (fs::path(dir) / (scene.meshes[k] + ".pc2")).string();
    if (!fs::exists(path)) throw InputError::message(path, "", "missing: Blender wrote no result for this garment");
    data::Pc2Cache cache = data::read_pc2(path);
    const std::int64_t v = seq.garments.at(k).n_vertices();
    if (cache.header.n_points != v)
      throw InputError(path, "numPoints", std::to_string(v), std::to_string(cache.header.n_points));
    if (cache.header.n_samples < scene.frames)
      throw InputError(path, "numSamples", "at least " + std::to_string(scene.frames),
                       std::to_string(cache.header.n_samples));
    run.garments.push_back(std::move(cache.positions));
  }
  const std::string timing = (fs::path(dir) / "timing.txt").string();
  std::ifstream in(timing);
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string key;
    double value = 0;
    if (fields >> key >> value && key == "ms_per_frame") run.ms_per_frame = value;
  }
  return run;
}

}  // namespace layers::generate
