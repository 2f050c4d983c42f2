// plugins/layersnet/src/factory.h -- LayersNet's name, description and
// factory for the registry, torch-free (register.cpp needs no torch).
#pragma once

#include <memory>

namespace layers::cfg {
struct Node;
}
namespace layers::zoo {
class Model;
}

namespace layers::layersnet {

inline constexpr const char* kName = "layersnet";
inline constexpr const char* kDescription =
    "LayersNet: UV patches + body/wind/gravity/attribute tokens, TIE attention (E^M and E^W heads), "
    "acceleration decoder";

// Reads the parameters (InputError naming the key) and builds the model.
std::shared_ptr<zoo::Model> make_layersnet(const cfg::Node& params);

}  // namespace layers::layersnet
