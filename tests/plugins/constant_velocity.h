// tests/plugins/constant_velocity.h -- a tiny real model for the plugin
// tests: p(t+1) = p(t) + (1 - damping) (p(t) - p(t-1)), with damping a
// learnable scalar initialised from the `damping` parameter (0..1,
// default 0: pure constant velocity). Torch-free declaration.
#pragma once

#include "layers/zoo/registry.h"

namespace layers::test {

std::shared_ptr<zoo::Model> make_constant_velocity(const cfg::Node& params);
inline constexpr zoo::ModelSpec kConstantVelocity{"test_constant_velocity",
                                                  "test model: constant velocity with one learnable damping scalar",
                                                  make_constant_velocity};

}  // namespace layers::test
