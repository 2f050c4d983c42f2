// layers/generate/quantile.h -- the nearest-rank quantile the generator's
// reports use (the cross-check's stretch p99, the spread of `layers
// validate --physics` over sequences).
#pragma once

#include <vector>

namespace layers::generate {

// The p-quantile (0..1, nearest rank) of `values` (reordered); 0 when empty.
double quantile(std::vector<float>& values, double p);

}  // namespace layers::generate
