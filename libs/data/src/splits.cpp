// splits.yaml reading and writing (see splits.h).
#include "layers/data/splits.h"

#include <algorithm>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "splits_source.h"
#include "yaml_util.h"

namespace layers::data {
namespace {

int standard_rank(const std::string& name) {
  if (name == "train") return 0;
  if (name == "val") return 1;
  if (name == "test") return 2;
  return 3;
}

}  // namespace

void Splits::set(const std::string& name, std::vector<std::string> ids) {
  for (auto& [n, list] : sets_) {
    if (n == name) {
      list = std::move(ids);
      return;
    }
  }
  sets_.emplace_back(name, std::move(ids));
}

bool Splits::has(const std::string& name) const {
  return std::any_of(sets_.begin(), sets_.end(), [&](const auto& s) { return s.first == name; });
}

const std::vector<std::string>& Splits::get(const std::string& name) const {
  for (const auto& [n, list] : sets_) {
    if (n == name) return list;
  }
  std::string names;
  for (const auto& n : this->names()) names += (names.empty() ? "" : ", ") + n;
  throw InputError(source_.empty() ? std::string("splits.yaml") : source_, name, "a split named '" + name + "'",
                   names.empty() ? std::string("no splits") : "only " + names);
}

std::vector<std::string> Splits::names() const {
  std::vector<std::string> out;
  for (const auto& s : sets_) out.push_back(s.first);
  std::stable_sort(out.begin(), out.end(),
                   [](const std::string& a, const std::string& b) { return standard_rank(a) < standard_rank(b); });
  return out;
}

std::string splits_to_yaml(const Splits& splits) {
  YAML::Emitter out;
  out << YAML::BeginMap;
  for (const auto& name : splits.names()) {
    out << YAML::Key << name << YAML::Value << YAML::Flow << splits.get(name);
  }
  out << YAML::EndMap;
  return std::string("# layers dataset splits: lists of sequence ids\n") + (splits.empty() ? "{}" : out.c_str()) + "\n";
}

std::string SplitsSource::where(const std::string& name, std::size_t index) const {
  const auto it = lines.find(name);
  if (it == lines.end() || index >= it->second.size() || it->second[index] <= 0) return path;
  return path + ":" + std::to_string(it->second[index]);
}

SplitsSource read_splits_source(const std::string& path) {
  SplitsSource source;
  source.splits.set_source(path);
  source.path = path;
  const YAML::Node root = load_yaml_file(path);
  if (root.IsNull()) return source;
  if (!root.IsMap()) {
    throw InputError(yaml_where(path, root), "", "a mapping of split names to lists of sequence ids",
                     "a list or scalar");
  }
  for (const auto& entry : root) {
    const auto name = yaml_scalar<std::string>(entry.first, path, "split name", "a string");
    const YAML::Node& list = entry.second;
    std::vector<std::string> ids;
    std::vector<int> lines;
    if (!list.IsNull()) {
      if (!list.IsSequence())
        throw InputError(yaml_where(path, list), name, "a list of sequence ids", "a scalar or mapping");
      for (const auto& item : list) {
        ids.push_back(yaml_scalar<std::string>(item, path, name, "a sequence id (string)"));
        lines.push_back(item.Mark().is_null() ? 0 : item.Mark().line + 1);
      }
    }
    if (source.splits.has(name))
      throw InputError(yaml_where(path, entry.first), name, "each split once", "a repeated split");
    source.splits.set(name, std::move(ids));
    source.lines[name] = std::move(lines);
  }
  return source;
}

Splits read_splits(const std::string& path) { return read_splits_source(path).splits; }

void write_splits(const std::string& path, const Splits& splits) { write_text_atomic(path, splits_to_yaml(splits)); }

}  // namespace layers::data
