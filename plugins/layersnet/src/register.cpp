// The layersnet plugin's entry point: registers the model (layersnet.h).
#include "layers/zoo/plugin.h"
#include "spec.h"

LAYERS_PLUGIN(registry) { registry.add(layers::layersnet::kLayersNet); }
