// plugins/layersnet/src/spec.h -- LayersNet's name, description and
// factory for the registry, torch-free (register.cpp needs no torch).
#pragma once

#include "layers/zoo/registry.h"

namespace layers::layersnet {

// Reads the parameters (InputError naming the key) and builds the model.
std::shared_ptr<zoo::Model> make_layersnet(const cfg::Node& params);
inline constexpr zoo::ModelSpec kLayersNet{
    "layersnet",
    "LayersNet: UV patches + body/wind/gravity/attribute tokens, TIE attention (E^M and E^W heads), "
    "acceleration decoder",
    make_layersnet};

}  // namespace layers::layersnet
