// What a scene holds that a training dataset did not (see unseen.h).
#include "layers/generate/unseen.h"

#include <filesystem>
#include <set>

#include "layers/data/manifest.h"

namespace layers::generate {

std::vector<std::string> unseen_in_training(const GeneratorConfig& scene, const std::string& training_dataset) {
  std::optional<GeneratorConfig> training;
  // A dataset folder, or one shard file of it (its folder's manifest).
  std::filesystem::path folder(training_dataset);
  if (std::filesystem::is_regular_file(folder)) folder = folder.parent_path();
  const std::string manifest = (folder / "dataset.yaml").string();
  if (std::filesystem::exists(manifest))
    training = recorded_generator_config(data::read_manifest(manifest).generator_yaml, manifest);
  std::set<std::string> seen;
  if (training)
    for (const auto& [file, hash] : training->garments.files) seen.insert(hash);
  std::vector<std::string> out;
  for (const auto& [file, hash] : scene.garments.files)
    if (!seen.count(hash) && std::filesystem::path(file).extension() != ".yaml") out.push_back("garment file " + file);
  if (scene.body.own && !(training && training->body.own && training->body.own->hash == scene.body.own->hash))
    out.push_back("body " + scene.body.own->file);
  if (!scene.body.own && training && training->body.own)
    out.push_back("body of ours (it was trained on a user's body)");
  return out;
}

}  // namespace layers::generate
