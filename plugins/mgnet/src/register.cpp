// The mgnet plugin: registers the MGNet model with the zoo.
#include "layers/mgnet/mgnet.h"
#include "layers/zoo/plugin.h"

LAYERS_PLUGIN(registry) { registry.add(layers::mgnet::kMgnet); }
