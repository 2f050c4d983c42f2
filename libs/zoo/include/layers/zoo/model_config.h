// layers/zoo/model_config.h -- the `model:` section of a config and
// creating the model it names.
//
//   model:
//     name: layersnet        # a registered model (layers models)
//     params: {width: 128}   # the plugin's own parameters
//
// Torch-free: Model is only forward-declared.
#pragma once

#include <memory>
#include <string>

#include "layers/core/config.h"

namespace layers::zoo {

class Model;
class Registry;

// The parameters of a model that has none: reading rejects any key
// (`params: {}` or no `params:` at all is fine).
struct NoParams {
  template <class V>
  void visit(V&) {}
};

struct ModelConfig {
  std::string name;
  cfg::Node params;

  template <class V>
  void visit(V& v) {
    v("name", name, cfg::opt().required().help("registered model name (see `layers models`)"));
    v("params", params, cfg::opt().help("the model's own parameters"));
  }
};

// Reads a `model:` section (at key path `path`) and creates the model it
// names. Errors name the config file and line and the full key path:
// `path`.name for an unknown model (listing the registered ones),
// `path`.params.<key> for a bad parameter.
std::shared_ptr<Model> create_model(const Registry& registry, const cfg::Node& section,
                                    const std::string& path = "model");

}  // namespace layers::zoo
