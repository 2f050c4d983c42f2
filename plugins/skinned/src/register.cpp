// Registers the "skinned" reference model (see spec.h).
#include "layers/zoo/plugin.h"
#include "spec.h"

LAYERS_PLUGIN(registry) { registry.add(layers::reference::kSkinned); }
