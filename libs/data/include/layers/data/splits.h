// layers/data/splits.h -- splits.yaml: named lists of sequence ids.
//
//   train: [id, ...]
//   val: [...]
//   test: [...]
//   T+W: [...]        # any further named subset
//
// `train`, `val` and `test` come first (in that order), other subsets
// follow in the order they were set or written.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace layers::data {

class Splits {
 public:
  // Replaces or adds a split.
  void set(const std::string& name, std::vector<std::string> ids);
  bool has(const std::string& name) const;
  // Throws InputError naming the file (source(), else "splits.yaml"), the
  // split and the available names if missing.
  const std::vector<std::string>& get(const std::string& name) const;
  std::vector<std::string> names() const;
  bool empty() const { return sets_.empty(); }
  // The file these splits were read from (read_splits), named in errors.
  void set_source(std::string path) { source_ = std::move(path); }
  const std::string& source() const { return source_; }

 private:
  std::vector<std::pair<std::string, std::vector<std::string>>> sets_;
  std::string source_;
};

std::string splits_to_yaml(const Splits& splits);
// Throws InputError with file:line on malformed YAML or a wrong structure
// (not a mapping of names to lists of ids).
Splits read_splits(const std::string& path);
// Atomic write.
void write_splits(const std::string& path, const Splits& splits);

}  // namespace layers::data
