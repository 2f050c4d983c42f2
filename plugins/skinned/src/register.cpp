// Registers the "skinned" reference model (see skinned_model.h).
#include "layers/zoo/plugin.h"
#include "skinned_model.h"

LAYERS_PLUGIN(registry) { registry.add(layers::reference::kSkinned); }
