// The nearest-rank quantile (see quantile.h).
#include "layers/generate/quantile.h"

#include <algorithm>
#include <cmath>
#include <cstddef>

namespace layers::generate {

double quantile(std::vector<float>& values, double p) {
  if (values.empty()) return 0.0;
  const double clamped = std::min(1.0, std::max(0.0, p));
  auto rank = static_cast<std::size_t>(std::ceil(clamped * static_cast<double>(values.size())));
  rank = std::min(values.size() - 1, rank == 0 ? 0 : rank - 1);
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

}  // namespace layers::generate
