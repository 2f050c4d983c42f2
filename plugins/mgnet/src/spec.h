// plugins/mgnet/src/spec.h -- creating the MGNet model (the motion-guided
// UV-space garment model; docs/mgnet.md). Torch-free declaration: the plugin
// registration and the tests create it through this factory.
#pragma once

#include "layers/zoo/registry.h"

namespace layers::mgnet {

// Reads the parameters (layers/mgnet/params.h; InputError on bad ones) and
// builds the model with freshly initialised weights (torch's global RNG).
std::shared_ptr<zoo::Model> make_mgnet(const cfg::Node& params);
inline constexpr zoo::ModelSpec kMgnet{
    "mgnet", "MGNet: UV-image conv encoder/decoder, displacement in tangent frames (garment-specific baseline)",
    make_mgnet};

}  // namespace layers::mgnet
