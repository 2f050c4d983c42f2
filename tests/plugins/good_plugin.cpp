// A working plugin: registers the constant-velocity test model.
#include "constant_velocity.h"
#include "layers/zoo/plugin.h"

// Defined with default visibility, yet not exported: layers_plugin()
// exports only the entry point (test_plugins checks that dlsym misses it).
extern "C" __attribute__((visibility("default"))) int layers_test_plugin_private_helper() { return 1; }

LAYERS_PLUGIN(registry) { registry.add(layers::test::kConstantVelocity); }
