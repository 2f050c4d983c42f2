// splits_source.h (private) -- splits.yaml with the line of every id, so
// that the reader and the validator can say where an unknown id is.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "layers/data/splits.h"

namespace layers::data {

struct SplitsSource {
  std::string path;
  Splits splits;
  std::map<std::string, std::vector<int>> lines;  // 1-based line of each id, per split
  // "path:line" of id number `index` of split `name`.
  std::string where(const std::string& name, std::size_t index) const;
};

SplitsSource read_splits_source(const std::string& path);

}  // namespace layers::data
