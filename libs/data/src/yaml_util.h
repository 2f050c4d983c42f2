// yaml_util.h (private) -- loading YAML files with errors that name the
// file and line (yaml-cpp lines are 0-based; messages use 1-based).
#pragma once

#include <yaml-cpp/yaml.h>

#include <string>

namespace layers::data {

// "path:line" of a node (just "path" when the node has no position).
std::string yaml_where(const std::string& path, const YAML::Node& node);
// Loads a file; InputError "path:line: malformed YAML (column c): ..." on
// parse errors, and the bounds of core/yaml_text.h.
YAML::Node load_yaml_file(const std::string& path);
// Parses text; `name` stands for the file in errors.
YAML::Node parse_yaml_text(const std::string& text, const std::string& name);
// Reads a scalar as T; InputError (file:line, key, expected, got) otherwise.
template <class T>
T yaml_scalar(const YAML::Node& node, const std::string& path, const std::string& key, const char* expected);

}  // namespace layers::data
