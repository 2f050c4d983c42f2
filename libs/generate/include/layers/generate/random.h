// layers/generate/random.h -- a small, platform-independent random number
// generator (SplitMix64) so that a dataset seed gives the same scenes, and
// so the same bytes, with any standard library.
#pragma once

#include <cstdint>
#include <vector>

namespace layers::generate {

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(seed) {}
  std::uint64_t next();
  double uniform();                                  // [0, 1)
  double uniform(double lo, double hi);              // [lo, hi)
  double uniform(const std::vector<double>& range);  // a [lo, hi] config pair
  int integer(int lo, int hi);                       // [lo, hi]
  // Index drawn with probability proportional to weights (not all zero).
  std::size_t pick(const std::vector<double>& weights);

 private:
  std::uint64_t state_;
};

// Mixes a seed with a stream number (e.g. the scene index) into a new seed.
std::uint64_t derive_seed(std::uint64_t seed, std::uint64_t stream);

}  // namespace layers::generate
