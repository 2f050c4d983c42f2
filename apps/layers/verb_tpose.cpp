// `layers tpose --config C [--scene K] --out DIR`: a generator config's
// scene in the T-pose its garments are fitted in, as OBJ files: body.obj
// and one <garment>.obj per garment with its UVs (none for a config whose
// garments.outfits is empty), and the body as a rig with the scene's
// motion, body.glb (generate/tpose.h). The reference a
// user models an own garment around, and a rig to animate
// (docs/own-data.md). Files already in DIR are never replaced.
#include <cstdio>
#include <filesystem>

#include "layers/core/atomic_file.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/export.h"
#include "layers/data/obj.h"
#include "layers/data/skinned_glb.h"
#include "layers/generate/imported_garment.h"
#include "layers/generate/tpose.h"
#include "verbs.h"

namespace layers::app {

VerbRun register_tpose(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("tpose", "Write a config's scene in its T-pose (body and garments) as OBJ files");
  struct Args {
    std::string config, out;
    std::vector<std::string> sets;
    int scene = 0;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--config", a->config, "generator config (configs/data/<name>.yaml)")
      ->required()
      ->check(CLI::ExistingFile);
  cmd->add_option("--set", a->sets, "override a config value: --set key.path=value (repeatable)");
  cmd->add_option("--scene", a->scene, "scene index (0-based), as `layers generate` draws it")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  cmd->add_option("--out", a->out, "output folder")->required();
  return [a]() {
    namespace fs = std::filesystem;
    // An empty outfit list is a body alone: body.obj and body.glb only.
    const generate::GeneratorConfig config = generate::load_generator_config(a->config, a->sets, false);
    if (a->scene >= config.sequences)
      throw InputError(a->config, "--scene", "a scene index below sequences (" + std::to_string(config.sequences) + ")",
                       std::to_string(a->scene));
    const generate::TPoseMeshes t = generate::tpose_meshes(config, a->scene);
    std::vector<std::string> garment_names;
    for (const auto& [name, mesh] : t.garments) garment_names.push_back(name);
    const std::vector<std::string> names = data::mesh_file_names(garment_names);  // as `layers export` names them
    std::vector<std::pair<std::string, const data::ObjMesh*>> files = {{names[0], &t.body}};
    for (std::size_t k = 0; k < t.garments.size(); ++k) files.emplace_back(names[k + 1], &t.garments[k].second);
    const fs::path rig_path = fs::path(a->out) / (names[0] + ".glb");
    for (const auto& [name, mesh] : files) {
      const fs::path path = fs::path(a->out) / (name + ".obj");
      if (fs::exists(path)) throw InputError(path.string(), "--out", "a folder without this file", "an existing file");
    }
    if (fs::exists(rig_path))
      throw InputError(rig_path.string(), "--out", "a folder without this file", "an existing file");
    fs::create_directories(a->out);
    for (const auto& [name, mesh] : files) {
      const std::string path = (fs::path(a->out) / (name + ".obj")).string();
      data::write_obj(path, *mesh);
      std::printf("wrote %s (%lld vertices)\n", path.c_str(), static_cast<long long>(mesh->n_vertices()));
    }
    if (t.rig.joint_names.empty()) {
      std::printf("note: no %s: the scene's body is a mesh sequence, which has no rig\n", rig_path.string().c_str());
    } else {
      write_new_text_file(rig_path.string(), data::skinned_glb_bytes(t.rig, static_cast<double>(data::kFps)),
                          "a folder without this file");
      std::printf("wrote %s (the body's rig and %lld frames: the T-pose, then the scene's motion)\n",
                  rig_path.string().c_str(),
                  static_cast<long long>(t.rig.joints.size() / (t.rig.joint_names.size() * 12)));
    }
    // What could be written is written (to look at); the scene itself is
    // refused, naming the config and the user's body file if any (issue 62).
    if (!t.problem.empty())
      throw InputError(a->config, "scene " + std::to_string(a->scene),
                       "a scene that can be simulated (its meshes that could be made are in " + a->out + ")",
                       t.problem + (config.body.own ? " (body.own.file " + config.body.own->file + ")" : ""));
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
