// layers/generate/quantile.h -- the nearest-rank quantile the generator's
// reports use (the cross-check's stretch p99, the spread of `layers
// validate --physics` over sequences), for float and double values.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

namespace layers::generate {

// The p-quantile (0..1, nearest rank) of `values` (reordered); 0 when empty.
template <class T>
double quantile(std::vector<T>& values, double p) {
  if (values.empty()) return 0.0;
  const double clamped = std::min(1.0, std::max(0.0, p));
  auto rank = static_cast<std::size_t>(std::ceil(clamped * static_cast<double>(values.size())));
  rank = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return static_cast<double>(values[rank]);
}

}  // namespace layers::generate
