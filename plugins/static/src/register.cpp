// Registers the "static" reference model (see static_model.h).
#include "layers/zoo/plugin.h"
#include "static_model.h"

LAYERS_PLUGIN(registry) {
  registry.add(layers::reference::kStaticName, layers::reference::kStaticDescription,
               layers::reference::make_static_model);
}
