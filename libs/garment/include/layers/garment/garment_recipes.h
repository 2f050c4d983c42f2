// layers/garment/garment_recipes.h -- the garment types as recipes: which
// pieces a type is made of and how its sizes are drawn from GarmentParams
// (a seeded, platform-independent random stream).
#pragma once

#include <cstdint>
#include <random>
#include <string>
#include <utility>
#include <vector>

#include "layers/garment/garment.h"
#include "layers/garment/garment_pieces.h"

namespace layers::garment {

// Uniform draws from a seeded 64-bit Mersenne twister (the same numbers on
// every platform, unlike std::uniform_real_distribution).
class Rng {
 public:
  explicit Rng(std::uint64_t seed) : engine_(seed) {}
  double uniform() { return static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  double range(const std::vector<double>& r) { return uniform(r[0], r[1]); }
  bool chance(double p) { return uniform() < p; }

 private:
  std::mt19937_64 engine_;
};

using Style = std::vector<std::pair<std::string, double>>;

// One recipe per garment type of layers::data's table (data/format.h):
// the pieces it is made of. A test checks the two name the same types.
struct Recipe {
  const char* type;
  void (*make)(const FitContext& ctx, const GarmentParams& params, Rng& rng, Pattern& pattern, Style& style);
};
const std::vector<Recipe>& recipes();

// Adds the pieces of `type` to `pattern` (its recipe), recording the drawn
// sizes in `style`. The type must be valid (see garment_types()).
void make_pattern(const std::string& type, const FitContext& ctx, const GarmentParams& params, Rng& rng,
                  Pattern& pattern, Style& style);

}  // namespace layers::garment
