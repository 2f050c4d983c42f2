// plugins/deepsd/src/spec.h -- the DeePSD model's registry entry: name,
// description and factory (torch-free, for the plugin's registration).
#pragma once

#include "layers/zoo/registry.h"

namespace layers::deepsd {

// Builds the model from its `model.params`; bad parameters are
// layers::InputError naming the key.
std::shared_ptr<zoo::Model> make_deepsd_model(const cfg::Node& params);
inline constexpr zoo::ModelSpec kDeepsd{
    "deepsd",
    "DeePSD: blend weights + pose-space deformations from garment graph descriptors, skinned with body/joints "
    "(static; wind input; deepsd+ = trained with the layer collision loss)",
    make_deepsd_model};

}  // namespace layers::deepsd
