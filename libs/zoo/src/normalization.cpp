// Normalization: NormStats -> float32 tensors (see normalization.h).
#include "layers/zoo/normalization.h"

namespace layers::zoo {
namespace {

NormPair pair_of(const data::Moments& m) {
  NormPair p;
  p.mean = at::tensor(std::vector<float>(m.mean.begin(), m.mean.end()), at::kFloat);
  p.std = at::tensor(std::vector<float>(m.std.begin(), m.std.end()), at::kFloat);
  return p;
}

}  // namespace

Normalization Normalization::identity() { return from_stats(data::NormStats{}); }

Normalization Normalization::from_stats(const data::NormStats& stats) {
  // The six quantities in data::for_each_quantity's order (same member names).
  std::vector<NormPair> pairs;
  data::for_each_quantity(stats, [&](const char*, const data::Moments& m) { pairs.push_back(pair_of(m)); });
  Normalization n;
  std::size_t i = 0;
  data::for_each_quantity(n, [&](const char*, NormPair& p) { p = pairs[i++]; });
  return n;
}

Normalization Normalization::to(const at::Device& device) const {
  Normalization out = *this;
  data::for_each_quantity(out, [&](const char*, NormPair& p) { p = NormPair{p.mean.to(device), p.std.to(device)}; });
  return out;
}

}  // namespace layers::zoo
