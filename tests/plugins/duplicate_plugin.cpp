// Registers a model of its own, then a name that the good plugin also
// registers: loading it after the good plugin must fail naming both files
// and leave neither of its models registered.
#include "constant_velocity.h"
#include "layers/zoo/plugin.h"

LAYERS_PLUGIN(registry) {
  registry.add("test_duplicate_extra", "registered before the duplicate", layers::test::make_constant_velocity);
  registry.add(layers::test::kConstantVelocity.name, "a second model under the good plugin's name",
               layers::test::make_constant_velocity);
}
