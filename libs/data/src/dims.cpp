// Dimension-symbol binding and shape messages (see dims.h).
#include "dims.h"

#include <cctype>

#include "layers/core/error.h"

namespace layers::data {
namespace {

std::string dims_text(const std::vector<std::uint64_t>& dims) {
  std::string out = "[";
  for (std::size_t i = 0; i < dims.size(); ++i) out += (i ? "," : "") + std::to_string(dims[i]);
  return out + "]";
}

}  // namespace

bool is_fixed_dim(const std::string& dim) { return !dim.empty() && std::isdigit(static_cast<unsigned char>(dim[0])); }

void DimBinder::bind(const std::string& symbol, std::int64_t value, const std::string& source) {
  bound_[symbol] = Bound{value, source};
}

std::optional<std::int64_t> DimBinder::get(const std::string& symbol) const {
  const auto it = bound_.find(symbol);
  if (it == bound_.end()) return std::nullopt;
  return it->second.value;
}

std::vector<std::uint64_t> DimBinder::resolve(const ArraySpec& spec) const {
  std::vector<std::uint64_t> out;
  for (const auto& dim : spec.dims) {
    if (is_fixed_dim(dim)) {
      out.push_back(std::stoull(dim));
    } else {
      const auto value = get(dim);
      if (!value) throw Error("layers-h5: dimension " + dim + " of " + spec.path + " is not known yet");
      out.push_back(static_cast<std::uint64_t>(*value));
    }
  }
  return out;
}

std::optional<std::string> DimBinder::match(const ArraySpec& spec, const std::vector<std::uint64_t>& got,
                                            const std::string& source) {
  const std::string expected = std::string(dtype_name(spec.dtype)) + " " + spec.shape_text();
  const std::string got_text = "got " + dims_text(got);
  if (got.size() != spec.dims.size()) {
    return "expected " + expected + " (rank " + std::to_string(spec.dims.size()) + "), " + got_text + " (rank " +
           std::to_string(got.size()) + ")";
  }
  std::string conflicts;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const std::string& dim = spec.dims[i];
    if (is_fixed_dim(dim)) {
      if (got[i] != std::stoull(dim)) return "expected " + expected + ", " + got_text;
      continue;
    }
    const auto it = bound_.find(dim);
    if (it != bound_.end() && static_cast<std::uint64_t>(it->second.value) != got[i]) {
      conflicts += (conflicts.empty() ? "" : ", ") + dim + "=" + std::to_string(it->second.value) + " (as in " +
                   it->second.source + ")";
    }
  }
  if (!conflicts.empty()) return "expected " + expected + " with " + conflicts + ", " + got_text;
  for (std::size_t i = 0; i < got.size(); ++i) {
    const std::string& dim = spec.dims[i];
    if (!is_fixed_dim(dim) && !bound_.count(dim)) bind(dim, static_cast<std::int64_t>(got[i]), source);
  }
  return std::nullopt;
}

std::optional<std::vector<std::uint64_t>> DimBinder::infer(const ArraySpec& spec, std::uint64_t size,
                                                           std::string& message) const {
  std::vector<std::uint64_t> dims(spec.dims.size(), 0);
  std::uint64_t known = 1;
  int unknown = -1;
  for (std::size_t i = 0; i < spec.dims.size(); ++i) {
    const std::string& dim = spec.dims[i];
    if (is_fixed_dim(dim)) {
      dims[i] = std::stoull(dim);
    } else if (const auto value = get(dim)) {
      dims[i] = static_cast<std::uint64_t>(*value);
    } else if (unknown < 0) {
      unknown = static_cast<int>(i);
      continue;
    } else {
      throw Error("layers-h5: two unknown dimensions in " + spec.path);
    }
    known *= dims[i];
  }
  if (unknown >= 0) {
    if (known == 0 || size % known != 0) {
      message = "expected " + std::string(dtype_name(spec.dtype)) + " " + spec.shape_text() + ": a multiple of " +
                std::to_string(known) + " elements, got " + std::to_string(size);
      return std::nullopt;
    }
    dims[static_cast<std::size_t>(unknown)] = size / known;
  } else if (known != size) {
    std::string bound_text;
    for (const auto& dim : spec.dims) {
      if (is_fixed_dim(dim)) continue;
      const auto& b = bound_.at(dim);
      bound_text +=
          (bound_text.empty() ? "" : ", ") + dim + "=" + std::to_string(b.value) + " (as in " + b.source + ")";
    }
    message = "expected " + std::string(dtype_name(spec.dtype)) + " " + spec.shape_text() +
              (bound_text.empty() ? "" : " with " + bound_text) + " = " + std::to_string(known) + " elements, got " +
              std::to_string(size);
    return std::nullopt;
  }
  return dims;
}

}  // namespace layers::data
