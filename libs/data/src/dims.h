// dims.h (private) -- binding the dimension symbols of the schema.
//
// A DimBinder remembers, for each symbol (T, Vb, V, ...), its value and
// where it was first seen ("the n_frames attribute", "/seq/a/body/positions").
// Matching a shape against an ArraySpec checks rank and fixed sizes, checks
// bound symbols and binds the unbound ones, and describes any mismatch in
// a message such as
//   expected float32 [T,V,3] with V=300 (as in /seq/a/garments/0/rest), got [20,299,3]
// The same binder checks files (validator, reader index) and in-memory
// sequences (writer), so "consistent sizes" means one thing everywhere.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "layers/data/format.h"

namespace layers::data {

class DimBinder {
 public:
  void bind(const std::string& symbol, std::int64_t value, const std::string& source);
  std::optional<std::int64_t> get(const std::string& symbol) const;
  // Resolves a spec to concrete sizes; every symbol must be bound.
  std::vector<std::uint64_t> resolve(const ArraySpec& spec) const;

  // Matches `got` against `spec`; on success binds the spec's unbound
  // symbols to `source` and returns nullopt, else returns the message
  // "expected <shape...>, got <dims>".
  std::optional<std::string> match(const ArraySpec& spec, const std::vector<std::uint64_t>& got,
                                   const std::string& source);

  // For flat in-memory arrays: the dims that a flat array of `size`
  // elements has under `spec`, deriving at most one unbound symbol.
  // Returns nullopt and sets `message` when size does not fit.
  std::optional<std::vector<std::uint64_t>> infer(const ArraySpec& spec, std::uint64_t size,
                                                  std::string& message) const;

 private:
  struct Bound {
    std::int64_t value;
    std::string source;
  };
  std::map<std::string, Bound> bound_;
};

bool is_fixed_dim(const std::string& dim);

}  // namespace layers::data
