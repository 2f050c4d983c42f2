// layers/generate/unseen.h -- what a scene holds that a model's training
// data did not (`layers animate --model`): a user's garment file or body
// whose contents (their recorded content hashes, garments.files and
// body.own.hash) are not among those of the dataset the model was trained
// on. A trained model may be rolled out on them; the output says so.
#pragma once

#include <string>
#include <vector>

#include "layers/generate/generator_config.h"

namespace layers::generate {

// One line per unseen input ("garment file mine/dress.obj", "body
// mine/character.glb", or our body for a model trained on a user's);
// empty when everything was in the training data. `training_dataset`:
// the folder (or a shard file of it) the model was trained on; a dataset
// without a recorded generator config saw no user file.
std::vector<std::string> unseen_in_training(const GeneratorConfig& scene, const std::string& training_dataset);

}  // namespace layers::generate
