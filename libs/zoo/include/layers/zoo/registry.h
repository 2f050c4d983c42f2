// layers/zoo/registry.h -- model factories by name.
//
// Plugins add their models here (see plugin.h); experiments create them by
// name with their parameters. Torch stays out of this header (Model is only
// forward-declared) so that the CLI can list models cheaply. Not
// thread-safe: fill it once at start-up, then read it.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace layers::cfg {
struct Node;
}

namespace layers::zoo {

class Model;

// Builds a model from its parameters (the `params` tree of an experiment
// config). Factories report bad parameters with layers::InputError
// (cfg::read does that for typed parameter structs).
using ModelFactory = std::function<std::shared_ptr<Model>(const cfg::Node& params)>;

// A model as its plugin declares it (next to the model, torch-free):
// registry name, one-line description, factory.
struct ModelSpec {
  const char* name;
  const char* description;
  std::shared_ptr<Model> (*make)(const cfg::Node& params);
};

struct ModelEntry {
  std::string name;
  std::string description;  // one line, shown by `layers models`
  std::string plugin_path;  // the shared library that registered it, or "<built-in>"
  ModelFactory factory;
};

namespace detail {
struct RegistryLoading;  // the plugin loader's access to a registry
}

class Registry {
 public:
  Registry();
  ~Registry();
  Registry(const Registry&) = delete;
  Registry& operator=(const Registry&) = delete;

  // Registers a factory. Names are letters, digits, '_', '-' and '.'.
  // `plugin_path` defaults to the plugin being loaded (or "<built-in>"
  // outside a plugin). A name registered twice is a layers::InputError
  // naming both plugin files.
  void add(const std::string& name, const std::string& description, ModelFactory factory,
           const std::string& plugin_path = "");

  // add(spec.name, spec.description, spec.make).
  void add(const ModelSpec& spec);

  bool contains(const std::string& name) const;
  // Registered names, sorted.
  std::vector<std::string> names() const;
  // Every entry, sorted by name.
  std::vector<ModelEntry> entries() const;
  // nullptr if unknown.
  const ModelEntry* find(const std::string& name) const;

  // Runs the factory of `name`. Unknown name: layers::InputError listing
  // every registered model (or saying that none is registered and where
  // plugins are searched). Factory errors propagate unchanged.
  std::shared_ptr<Model> create(const std::string& name, const cfg::Node& params) const;

  // "registered models: a (path), b (path)" or, when empty, where plugins
  // are searched.
  std::string summary() const;

  // Called by the entry point that LAYERS_PLUGIN generates when the
  // plugin's registration code throws: the loader reports the message.
  void report_plugin_error(const std::string& message);

 private:
  friend struct detail::RegistryLoading;
  std::map<std::string, ModelEntry> entries_;
  std::string loading_;                     // plugin being loaded, if any
  std::vector<std::string> plugin_errors_;  // reported while loading it
};

}  // namespace layers::zoo
