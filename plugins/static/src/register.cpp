// Registers the "static" reference model (see static_model.h).
#include "layers/zoo/plugin.h"
#include "static_model.h"

LAYERS_PLUGIN(registry) { registry.add(layers::reference::kStatic); }
