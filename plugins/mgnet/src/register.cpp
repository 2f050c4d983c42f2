// The mgnet plugin: registers the MGNet model with the zoo.
#include "layers/zoo/plugin.h"
#include "spec.h"

LAYERS_PLUGIN(registry) { registry.add(layers::mgnet::kMgnet); }
