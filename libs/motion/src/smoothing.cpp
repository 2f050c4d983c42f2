// Smoothing of per-frame curves (see smoothing.h).
#include "smoothing.h"

#include <algorithm>
#include <cmath>

namespace layers::motion {

std::vector<double> gaussian_smooth(const std::vector<double>& v, double sigma) {
  const int n = static_cast<int>(v.size());
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> out(n);
  for (int i = 0; i < n; ++i) {
    double sum = 0.0, weight = 0.0;
    for (int k = -radius; k <= radius; ++k) {
      const double g = std::exp(-0.5 * k * k / (sigma * sigma));
      sum += g * v[std::clamp(i + k, 0, n - 1)];
      weight += g;
    }
    out[i] = sum / weight;
  }
  return out;
}

std::vector<double> upper_envelope(const std::vector<double>& v, double sigma) {
  const int n = static_cast<int>(v.size());
  const int radius = static_cast<int>(std::ceil(3 * sigma));
  std::vector<double> wide(n, -1e300);
  for (int i = 0; i < n; ++i)
    for (int k = std::max(0, i - radius); k <= std::min(n - 1, i + radius); ++k) wide[i] = std::max(wide[i], v[k]);
  return gaussian_smooth(wide, sigma);
}

std::vector<double> lower_envelope(const std::vector<double>& v, double sigma) {
  std::vector<double> neg(v.size());
  std::transform(v.begin(), v.end(), neg.begin(), [](double x) { return -x; });
  std::vector<double> out = upper_envelope(neg, sigma);
  for (double& x : out) x = -x;
  return out;
}

void fill_gaps(std::vector<double>& v, double fallback) {
  const int n = static_cast<int>(v.size());
  int prev = -1;
  for (int i = 0; i <= n; ++i) {
    if (i < n && std::isnan(v[i])) continue;
    const double a = prev >= 0 ? v[prev] : (i < n ? v[i] : fallback);
    const double b = i < n ? v[i] : a;
    for (int k = prev + 1; k < i; ++k) v[k] = a + (b - a) * (k - prev) / static_cast<double>(i - prev);
    prev = i;
  }
}

}  // namespace layers::motion
