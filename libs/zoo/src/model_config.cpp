// Creating a model from its config section, with config paths in errors
// (see model_config.h).
#include "layers/zoo/model_config.h"

#include "layers/core/error.h"
#include "layers/zoo/registry.h"

namespace layers::zoo {

std::shared_ptr<Model> create_model(const Registry& registry, const cfg::Node& section, const std::string& path) {
  ModelConfig config = cfg::read<ModelConfig>(section, path);
  if (!registry.contains(config.name))
    throw InputError::message(section.find("name")->where(), path + ".name",
                              "unknown model '" + config.name + "'; " + registry.summary());
  if (config.params.kind == cfg::Node::Kind::Null) {
    // No `params:`: the plugin's defaults (an empty mapping where the section is).
    config.params.kind = cfg::Node::Kind::Map;
    config.params.file = section.file;
    config.params.line = section.line;
  }
  try {
    return registry.create(config.name, config.params);
  } catch (const InputError& e) {
    // Plugins read their parameters relative to `params`: prefix the path.
    const std::string prefix = path + ".params";
    std::string field = e.field().empty() || e.field() == "<top level>" ? prefix : prefix + "." + e.field();
    if (!e.expected().empty()) throw InputError(e.file(), field, e.expected(), e.got());
    throw;
  }
}

}  // namespace layers::zoo
