// What a scene holds that a training dataset did not (see unseen.h).
#include "layers/generate/unseen.h"

#include <filesystem>
#include <set>

#include "layers/data/manifest.h"

namespace layers::generate {

std::vector<std::string> unseen_in_training(const GeneratorConfig& scene, const std::string& training_dataset) {
  std::optional<GeneratorConfig> training;
  const std::string manifest = (std::filesystem::path(training_dataset) / "dataset.yaml").string();
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
  return out;
}

}  // namespace layers::generate
