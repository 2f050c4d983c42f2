// layers/core/yaml_text.h -- the one way YAML text becomes yaml-cpp's tree
// in the toolkit (configs, dataset manifests and splits, garment side
// files). Before the tree is built, a streaming pass over the parser's
// events counts values and nesting, so that a file of millions of list
// items or thousands of nesting levels is refused at the bound with a few
// kilobytes of memory, not after gigabytes of tree; a NUL byte is refused
// by position (YAML text holds none). Callers need yaml-cpp's headers for
// the returned tree.
#pragma once

#include <cstdint>
#include <string>

namespace YAML {
class Node;
}

namespace layers {

// The most values (scalars, nulls, aliases, lists and mappings) and the
// deepest nesting any YAML text the toolkit reads may hold.
inline constexpr std::int64_t kMaxYamlValues = 1000000;
inline constexpr int kMaxYamlDepth = 64;

// InputError naming `name` (and the line where known): a NUL byte, more
// values or deeper nesting than the bounds, or malformed YAML
// ("name:line: malformed YAML (column c): ...").
YAML::Node parse_yaml(const std::string& text, const std::string& name);

}  // namespace layers
