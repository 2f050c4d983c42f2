// The good plugin's registration, compiled as if against LibTorch 0.4.1
// (LAYERS_PLUGIN_TORCH_VERSION, see CMakeLists.txt): the ABI handshake must
// refuse it, name the mismatch and register nothing.
#include "constant_velocity.h"
#include "layers/zoo/plugin.h"

LAYERS_PLUGIN(registry) {
  registry.add("test_wrong_abi", layers::test::kConstantVelocity.description, layers::test::make_constant_velocity);
}
