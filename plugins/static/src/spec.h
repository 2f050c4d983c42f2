// plugins/static/src/spec.h -- the "static" reference model: every
// garment moves rigidly with the body root (pelvis) from the last known
// frame,
//   p(t+1) = R(t+1) R(t)^T (p(t) - root(t)) + root(t+1),
// with root / root_rot (w,x,y,z) from StepInput. No parameters, nothing to
// train: the anchor "a garment glued to the pelvis" for accuracy charts.
// Torch-free declaration.
#pragma once

#include "layers/zoo/registry.h"

namespace layers::reference {

// `params` must be empty (or absent); any key is a layers::InputError.
std::shared_ptr<zoo::Model> make_static_model(const cfg::Node& params);
inline constexpr zoo::ModelSpec kStatic{
    "static", "reference: garments move rigidly with the body root from the last frame (no parameters)",
    make_static_model};

}  // namespace layers::reference
