// Index, id, type and layer rules (see sequence_rules.h).
#include "sequence_rules.h"

#include <algorithm>

#include "layers/data/format.h"

namespace layers::data {

std::optional<std::string> check_index_range(const std::vector<std::int32_t>& values, std::int64_t lo, std::int64_t hi,
                                             std::size_t width) {
  std::size_t bad = 0, first = 0;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (values[i] < lo || values[i] >= hi) {
      if (bad++ == 0) first = i;
    }
  }
  if (bad == 0) return std::nullopt;
  return "expected indices in [" + std::to_string(lo) + "," + std::to_string(hi - 1) + "], got " + std::to_string(bad) +
         " out of range, first " + std::to_string(values[first]) + " at row " +
         std::to_string(first / std::max<std::size_t>(width, 1));
}

std::optional<std::string> check_joint_parents(const std::vector<std::int32_t>& parents) {
  const auto n = static_cast<std::int64_t>(parents.size());
  if (auto range = check_index_range(parents, -1, n, 1)) return range;
  for (std::int64_t j = 0; j < n; ++j) {
    if (parents[static_cast<std::size_t>(j)] == j) {
      return "expected a parent other than the joint itself (or -1), got joint " + std::to_string(j) +
             " as its own parent";
    }
  }
  return std::nullopt;
}

std::optional<std::string> check_sequence_id(const std::string& id) {
  if (id.empty() || id == "." || id == ".." || id.find('/') != std::string::npos) {
    return "expected a sequence id that is non-empty, has no '/' and is not '.' or '..', got '" + id + "'";
  }
  return std::nullopt;
}

std::optional<std::string> check_garment_type(const std::string& type) {
  if (is_garment_type(type)) return std::nullopt;
  std::string known;
  for (const auto& t : garment_types()) known += (known.empty() ? "" : ", ") + t;
  return "expected a garment type (one of " + known + "), got '" + type + "'";
}

std::optional<std::string> check_garment_layer(std::int64_t layer) {
  if (layer == 0 || layer == 1) return std::nullopt;
  return "expected layer 0 (inner) or 1 (outer), got " + std::to_string(layer);
}

bool is_reserved(const std::string& name, const std::vector<std::string>& reserved) {
  return std::find(reserved.begin(), reserved.end(), name) != reserved.end();
}

}  // namespace layers::data
