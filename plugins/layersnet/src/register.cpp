// The layersnet plugin's entry point: registers the model (layersnet.h).
#include "factory.h"
#include "layers/zoo/plugin.h"

LAYERS_PLUGIN(registry) { registry.add(layers::layersnet::kLayersNet); }
