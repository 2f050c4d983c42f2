// tests/support/garment_motion.h -- how tests compare two simulations of a
// scene: a garment's mean vertex speed (mm per frame, as the generator
// regression compares runs) and the mean distance between the same
// vertices of two runs (mm, over every frame).
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "layers/data/sequence.h"

namespace layers::test {

inline double garment_speed_mm(const data::GarmentData& g, std::int64_t frames) {
  const std::size_t n = g.rest.size();
  double sum = 0;
  for (std::int64_t t = 1; t < frames; ++t)
    for (std::size_t i = 0; i < n; i += 3) {
      const float* p = g.positions.data() + t * n + i;
      sum += std::sqrt(std::pow(p[0] - p[-n + 0], 2) + std::pow(p[1] - p[-n + 1], 2) + std::pow(p[2] - p[-n + 2], 2));
    }
  return 1000.0 * sum / static_cast<double>((frames - 1) * static_cast<std::int64_t>(n / 3));
}

inline double mean_distance_mm(const std::vector<float>& a, const std::vector<float>& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.size(); i += 3)
    sum += std::sqrt(std::pow(a[i] - b[i], 2) + std::pow(a[i + 1] - b[i + 1], 2) + std::pow(a[i + 2] - b[i + 2], 2));
  return 1000.0 * sum / static_cast<double>(a.size() / 3);
}

}  // namespace layers::test
