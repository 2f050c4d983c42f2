// Registers the DeePSD model (see deepsd_model.h).
#include "layers/zoo/plugin.h"
#include "spec.h"

LAYERS_PLUGIN(registry) { registry.add(layers::deepsd::kDeepsd); }
