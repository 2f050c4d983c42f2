// layers/core/config_node.h -- the configuration tree.
//
// YAML files are parsed into this small tree that remembers, for every
// value, the file and line it came from, so that errors found later (by the
// typed reader, by a plugin reading its own parameters) can still name
// file, line and key path. Files may `include:` a base file (or a list of
// them) whose values they override; the command line overrides both with
// `--set key.path=value`.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace layers::cfg {

struct Node {
  enum class Kind { Null, Scalar, Map, Seq };

  Kind kind = Kind::Null;
  std::string scalar;                             // Kind::Scalar
  std::vector<std::pair<std::string, Node>> map;  // Kind::Map, in file order
  std::vector<Node> seq;                          // Kind::Seq
  std::string file;                               // where the value was written
  int line = 0;                                   // 1-based; 0 if not from a file

  const Node* find(const std::string& key) const;
  Node* find(const std::string& key);
  // Finds a map entry, creating it (as Null) if missing.
  Node& child(const std::string& key);
  // Removes the map entry `key` if there is one.
  void erase(const std::string& key);
  // "file:line" (or "file" when the line is unknown).
  std::string where() const;
  std::string kind_name() const;
};

// Parses YAML text. `name` is used in error messages as the file name.
Node parse(const std::string& text, const std::string& name);

// Loads a YAML file and resolves its `include:` key (a path or a list of
// paths, relative to the including file): includes are loaded first, in
// order, and the file's own values override them. Cycles are errors.
Node load_file(const std::string& path);

// Recursively overrides `base` with `over`: maps merge key by key, any
// other value replaces. A Null in `over` removes nothing (YAML `~`
// resets the value to Null).
void merge(Node& base, const Node& over);

// Applies "key.path=value" (value parsed as YAML, e.g. `[1, 2]`). Errors
// name the assignment.
void apply_set(Node& root, const std::string& assignment);

// Emits the tree as YAML (keys in order).
std::string to_yaml(const Node& node);

}  // namespace layers::cfg
