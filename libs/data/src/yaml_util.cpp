// YAML loading with file:line errors (see yaml_util.h).
#include "yaml_util.h"

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/core/yaml_text.h"

namespace layers::data {

std::string yaml_where(const std::string& path, const YAML::Node& node) {
  const YAML::Mark mark = node.Mark();
  if (mark.is_null() || mark.line < 0) return path;
  return path + ":" + std::to_string(mark.line + 1);
}

YAML::Node parse_yaml_text(const std::string& text, const std::string& name) { return parse_yaml(text, name); }

YAML::Node load_yaml_file(const std::string& path) { return parse_yaml_text(read_text_file(path), path); }

template <class T>
T yaml_scalar(const YAML::Node& node, const std::string& path, const std::string& key, const char* expected) {
  if (!node.IsScalar()) {
    throw InputError(yaml_where(path, node), key, expected, node.IsNull() ? "nothing" : "a list or mapping");
  }
  try {
    return node.as<T>();
  } catch (const YAML::Exception&) {
    throw InputError(yaml_where(path, node), key, expected, "'" + node.Scalar() + "'");
  }
}

template std::string yaml_scalar<std::string>(const YAML::Node&, const std::string&, const std::string&, const char*);
template std::int64_t yaml_scalar<std::int64_t>(const YAML::Node&, const std::string&, const std::string&, const char*);
template std::uint64_t yaml_scalar<std::uint64_t>(const YAML::Node&, const std::string&, const std::string&,
                                                  const char*);

}  // namespace layers::data
