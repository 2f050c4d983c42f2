// SplitMix64 and the draws built on it (see random.h).
#include "layers/generate/random.h"

#include <cmath>

namespace layers::generate {

std::uint64_t Rng::next() {
  std::uint64_t z = (state_ += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}

double Rng::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

double Rng::uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }

double Rng::uniform(const std::vector<double>& range) { return uniform(range.at(0), range.at(1)); }

int Rng::integer(int lo, int hi) {
  return lo + static_cast<int>(std::floor(uniform() * static_cast<double>(hi - lo + 1)));
}

std::size_t Rng::pick(const std::vector<double>& weights) {
  double total = 0;
  for (double w : weights) total += w;
  double u = uniform() * total;
  for (std::size_t i = 0; i < weights.size(); ++i) {
    if (u < weights[i]) return i;
    u -= weights[i];
  }
  for (std::size_t i = weights.size(); i-- > 0;)
    if (weights[i] > 0) return i;
  return 0;
}

std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream) {
  Rng a(seed ^ (stream * 0xD1B54A32D192ED03ull));
  a.next();
  return a.next();
}

}  // namespace layers::generate
