// Parsing, include resolution, merging, --set overrides and emission of the
// configuration tree (see config_node.h).
#include "layers/core/config_node.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <sstream>

#include "layers/core/error.h"
#include "layers/core/install_paths.h"
#include "layers/core/text_file.h"
#include "layers/core/yaml_text.h"

namespace fs = std::filesystem;

namespace layers::cfg {

const Node* Node::find(const std::string& key) const {
  for (const auto& [k, v] : map)
    if (k == key) return &v;
  return nullptr;
}

Node* Node::find(const std::string& key) {
  for (auto& [k, v] : map)
    if (k == key) return &v;
  return nullptr;
}

void Node::erase(const std::string& key) {
  map.erase(std::remove_if(map.begin(), map.end(), [&](const auto& kv) { return kv.first == key; }), map.end());
}

Node& Node::child(const std::string& key) {
  if (Node* existing = find(key)) return *existing;
  if (kind == Kind::Null) kind = Kind::Map;
  map.emplace_back(key, Node{});
  Node& added = map.back().second;
  added.file = file;
  added.line = line;
  return added;
}

std::string Node::where() const {
  std::string out = file.empty() ? std::string("<config>") : file;
  if (line > 0) out += ":" + std::to_string(line);
  return out;
}

std::string Node::kind_name() const {
  switch (kind) {
    case Kind::Null:
      return "nothing";
    case Kind::Scalar:
      return "a scalar";
    case Kind::Map:
      return "a mapping";
    case Kind::Seq:
      return "a list";
  }
  return "?";
}

namespace {

// Bounds of a config: aliases make copies (a few hundred bytes can expand
// to billions of values), so values and depth are counted as they convert.
// Keys and scalars are counted in bytes as well (one aliased long string
// is one value many times over), and includes in files loaded (a file may
// include another several times, and that one others).
constexpr std::size_t kMaxConfigBytes = 16u << 20;
constexpr std::int64_t kMaxConfigExpandedBytes = 64 << 20;
constexpr int kMaxConfigFiles = 256;

struct Budget {
  std::int64_t values = 0, bytes = 0;
  int depth = 0;
};

void spend_bytes(Budget& budget, std::size_t bytes, const std::string& name) {
  budget.bytes += static_cast<std::int64_t>(bytes);
  if (budget.bytes > kMaxConfigExpandedBytes)
    throw InputError(name, "",
                     "a config of at most " + std::to_string(kMaxConfigExpandedBytes >> 20) + " MiB of keys and values",
                     "more (YAML aliases expand into copies)");
}

Node convert(const YAML::Node& y, const std::string& name, Budget& budget) {
  if (++budget.values > kMaxYamlValues)
    throw InputError(name, "", "a config of at most " + std::to_string(kMaxYamlValues) + " values",
                     "more (YAML aliases expand into copies)");
  if (budget.depth >= kMaxYamlDepth)
    throw InputError(name + ":" + std::to_string(y.Mark().line + 1), "",
                     "values nested at most " + std::to_string(kMaxYamlDepth) + " levels deep", "deeper nesting");
  struct Deeper {
    Budget& b;
    explicit Deeper(Budget& b) : b(b) { ++b.depth; }
    ~Deeper() { --b.depth; }
  } deeper(budget);
  Node out;
  out.file = name;
  out.line = y.Mark().line >= 0 ? y.Mark().line + 1 : 0;
  switch (y.Type()) {
    case YAML::NodeType::Undefined:
    case YAML::NodeType::Null:
      out.kind = Node::Kind::Null;
      break;
    case YAML::NodeType::Scalar:
      out.kind = Node::Kind::Scalar;
      spend_bytes(budget, y.Scalar().size(), name);
      out.scalar = y.Scalar();
      break;
    case YAML::NodeType::Sequence:
      out.kind = Node::Kind::Seq;
      for (const auto& item : y) out.seq.push_back(convert(item, name, budget));
      break;
    case YAML::NodeType::Map:
      out.kind = Node::Kind::Map;
      for (const auto& kv : y) {
        std::string key = kv.first.as<std::string>();
        spend_bytes(budget, key.size(), name);
        if (out.find(key))
          throw InputError::message(name + ":" + std::to_string(kv.first.Mark().line + 1), key, "duplicate key");
        out.map.emplace_back(key, convert(kv.second, name, budget));
      }
      break;
  }
  return out;
}

// An include's file: relative to the including file's folder; a relative
// path under configs/ that is not there is the installed toolkit's config
// (<prefix>/share/layers/configs), so a config outside a clone can include
// the shipped ones as a clone's do.
fs::path include_target(const fs::path& including, const fs::path& include) {
  if (!include.is_relative()) return include;
  const fs::path here = including.parent_path() / include;
  if (fs::exists(here)) return here;
  const auto first = include.begin();
  if (first == include.end() || *first != "configs") return here;
  const std::string installed = installed_dir(kInstalledConfigDir);
  if (installed.empty()) return here;
  fs::path shipped = installed;
  for (auto part = std::next(first); part != include.end(); ++part) shipped /= *part;
  return fs::exists(shipped) ? shipped : here;
}

Node load_recursive(const fs::path& path, std::vector<std::string>& stack, int& files) {
  std::string name = path.string();
  if (++files > kMaxConfigFiles)
    throw InputError::message(name, "include",
                              "one file more than the " + std::to_string(kMaxConfigFiles) +
                                  " a config may load with its includes (an include loads its file each time)");
  std::error_code ec;
  fs::path canonical = fs::weakly_canonical(path, ec);
  std::string key = ec ? name : canonical.string();
  for (const auto& open : stack)
    if (open == key) throw InputError::message(name, "include", "include cycle through " + stack.front());
  Node own = parse(read_text_file(name), name);
  if (own.kind == Node::Kind::Null) {
    own.kind = Node::Kind::Map;
  } else if (own.kind != Node::Kind::Map) {
    throw InputError(own.where(), "<top level>", "a mapping of keys", own.kind_name());
  }

  const Node* include = own.find("include");
  if (!include) return own;

  std::vector<const Node*> paths;
  if (include->kind == Node::Kind::Scalar) {
    paths.push_back(include);
  } else if (include->kind == Node::Kind::Seq) {
    for (const auto& p : include->seq) {
      if (p.kind != Node::Kind::Scalar) throw InputError(p.where(), "include", "a file path", p.kind_name());
      paths.push_back(&p);
    }
  } else {
    throw InputError(include->where(), "include", "a file path or a list of paths", include->kind_name());
  }

  stack.push_back(key);
  Node result;
  result.kind = Node::Kind::Map;
  result.file = name;
  for (const Node* p : paths) {
    const fs::path target = include_target(path, fs::path(p->scalar));
    if (!fs::exists(target)) throw InputError(p->where(), "include", "an existing file", "'" + target.string() + "'");
    merge(result, load_recursive(target, stack, files));
  }
  stack.pop_back();
  Node rest = own;
  rest.erase("include");
  merge(result, rest);
  return result;
}

void emit(YAML::Emitter& out, const Node& node) {
  switch (node.kind) {
    case Node::Kind::Null:
      out << YAML::Null;
      break;
    case Node::Kind::Scalar:
      out << node.scalar;
      break;
    case Node::Kind::Seq:
      out << YAML::BeginSeq;
      for (const auto& item : node.seq) emit(out, item);
      out << YAML::EndSeq;
      break;
    case Node::Kind::Map:
      out << YAML::BeginMap;
      for (const auto& [k, v] : node.map) {
        out << YAML::Key << k << YAML::Value;
        emit(out, v);
      }
      out << YAML::EndMap;
      break;
  }
}

}  // namespace

Node parse(const std::string& text, const std::string& name) {
  if (text.size() > kMaxConfigBytes)
    throw InputError(name, "", "a config of at most " + std::to_string(kMaxConfigBytes >> 20) + " MiB",
                     std::to_string(text.size()) + " bytes");
  Budget budget;
  return convert(parse_yaml(text, name), name, budget);
}

Node load_file(const std::string& path) {
  std::vector<std::string> stack;
  int files = 0;
  return load_recursive(fs::path(path), stack, files);
}

void merge(Node& base, const Node& over) {
  if (base.kind == Node::Kind::Map && over.kind == Node::Kind::Map) {
    for (const auto& [k, v] : over.map) {
      if (Node* existing = base.find(k))
        merge(*existing, v);
      else
        base.map.emplace_back(k, v);
    }
    return;
  }
  base = over;
}

void apply_set(Node& root, const std::string& assignment) {
  const std::string source = "--set " + assignment;
  auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InputError("--set", "'" + assignment + "'", "key.path=value", "no '=' or empty key");
  std::string path = assignment.substr(0, eq);
  const std::string text = assignment.substr(eq + 1);
  if (text.find_first_not_of(" \t") == std::string::npos)
    throw InputError("--set", assignment.substr(0, eq), "a value after '=' (write null for none)", "nothing");
  Node value = parse(text, "--set");
  // Values set from the command line point at the command line.
  std::vector<Node*> todo{&value};
  while (!todo.empty()) {
    Node* n = todo.back();
    todo.pop_back();
    n->file = source;
    n->line = 0;
    for (auto& kv : n->map) todo.push_back(&kv.second);
    for (auto& s : n->seq) todo.push_back(&s);
  }
  Node* at = &root;
  std::size_t begin = 0;
  while (true) {
    std::size_t dot = path.find('.', begin);
    std::string key = path.substr(begin, dot == std::string::npos ? std::string::npos : dot - begin);
    if (key.empty()) throw InputError("--set", "'" + assignment + "'", "a key path like model.width", "an empty key");
    if (at->kind != Node::Kind::Map && at->kind != Node::Kind::Null)
      throw InputError("--set", path.substr(0, begin ? begin - 1 : 0), "a mapping to set '" + key + "' in",
                       at->kind_name() + " (from " + at->where() + ")");
    if (at->kind == Node::Kind::Null) {
      at->kind = Node::Kind::Map;
      at->file = source;
    }
    at = &at->child(key);
    if (dot == std::string::npos) break;
    begin = dot + 1;
  }
  merge(*at, value);
}

std::string to_yaml(const Node& node) {
  YAML::Emitter out;
  emit(out, node);
  return std::string(out.c_str()) + "\n";
}

}  // namespace layers::cfg
