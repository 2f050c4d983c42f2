// The good plugin's registration, compiled with LAYERS_ZOO_API_VERSION=999
// (see CMakeLists.txt): the loader must refuse it and ask for a rebuild.
#include "constant_velocity.h"
#include "layers/zoo/plugin.h"

static_assert(LAYERS_ZOO_API_VERSION == 999, "this test plugin must be built for API v999");

LAYERS_PLUGIN(registry) {
  registry.add("test_wrong_api", layers::test::kConstantVelocity.description, layers::test::make_constant_velocity);
}
