// Registers the DeePSD model (see deepsd_model.h).
#include "factory.h"
#include "layers/zoo/plugin.h"

LAYERS_PLUGIN(registry) { registry.add(layers::deepsd::kDeepsd); }
