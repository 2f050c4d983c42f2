// A working plugin: registers the constant-velocity test model.
#include "constant_velocity.h"
#include "layers/zoo/plugin.h"

LAYERS_PLUGIN(registry) {
  registry.add(layers::test::kConstantVelocityName, layers::test::kConstantVelocityDescription,
               layers::test::make_constant_velocity);
}
