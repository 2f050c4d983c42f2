// Model registry (see registry.h).
#include "layers/zoo/registry.h"

#include <algorithm>

#include "layers/core/config_node.h"
#include "layers/core/error.h"

namespace layers::zoo {
namespace {

constexpr const char* kBuiltIn = "<built-in>";

bool valid_name(const std::string& name) {
  return !name.empty() && std::all_of(name.begin(), name.end(), [](char c) {
    return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_' || c == '-' ||
           c == '.';
  });
}

}  // namespace

Registry::Registry() = default;
Registry::~Registry() = default;

void Registry::add(const std::string& name, const std::string& description, ModelFactory factory,
                   const std::string& plugin_path) {
  std::string path = !plugin_path.empty() ? plugin_path : !loading_.empty() ? loading_ : kBuiltIn;
  if (!valid_name(name)) {
    throw InputError(path, "model name", "letters, digits, '_', '-' or '.'", "'" + name + "'");
  }
  if (!factory) throw Error(path + ": model '" + name + "' registered without a factory");
  auto found = entries_.find(name);
  if (found != entries_.end()) {
    throw InputError::message(path, "model '" + name + "'",
                              "registered twice: by " + found->second.plugin_path + " and by " + path +
                                  "; model names must be unique, remove or rename one of the plugins");
  }
  entries_.emplace(name, ModelEntry{name, description, path, std::move(factory)});
}

void Registry::add(const ModelSpec& spec) { add(spec.name, spec.description, spec.make); }

bool Registry::contains(const std::string& name) const { return entries_.count(name) > 0; }

std::vector<std::string> Registry::names() const {
  std::vector<std::string> out;
  for (const auto& [name, entry] : entries_) out.push_back(name);
  return out;
}

std::vector<ModelEntry> Registry::entries() const {
  std::vector<ModelEntry> out;
  for (const auto& [name, entry] : entries_) out.push_back(entry);
  return out;
}

const ModelEntry* Registry::find(const std::string& name) const {
  auto found = entries_.find(name);
  return found == entries_.end() ? nullptr : &found->second;
}

std::shared_ptr<Model> Registry::create(const std::string& name, const cfg::Node& params) const {
  const ModelEntry* entry = find(name);
  if (!entry) throw InputError::message(params.file, "model", "unknown model '" + name + "'; " + summary());
  std::shared_ptr<Model> model = entry->factory(params);
  if (!model) throw Error(entry->plugin_path + ": the factory of model '" + name + "' returned no model");
  return model;
}

std::string Registry::summary() const {
  if (entries_.empty())
    return "no models registered; check LAYERS_PLUGIN_PATH (plugins are liblayers_plugin_<name>.so files, "
           "searched in LAYERS_PLUGIN_PATH, then in plugins/ next to the layers binary, then beside it, then in "
           "<prefix>/lib/layers/plugins)";
  std::string text = "registered models: ";
  const char* sep = "";
  for (const auto& [n, e] : entries_) {
    text += sep + n + " (" + e.plugin_path + ")";
    sep = ", ";
  }
  return text;
}

void Registry::report_plugin_error(const std::string& message) { plugin_errors_.push_back(message); }

}  // namespace layers::zoo
