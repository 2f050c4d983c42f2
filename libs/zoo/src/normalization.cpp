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

template <class F>
Normalization map_pairs(const Normalization& n, F&& f) {
  Normalization out;
  out.garment_position = f(n.garment_position);
  out.garment_velocity = f(n.garment_velocity);
  out.garment_acceleration = f(n.garment_acceleration);
  out.body_position = f(n.body_position);
  out.body_velocity = f(n.body_velocity);
  out.body_acceleration = f(n.body_acceleration);
  return out;
}

}  // namespace

Normalization Normalization::identity() { return from_stats(data::NormStats{}); }

Normalization Normalization::from_stats(const data::NormStats& stats) {
  Normalization n;
  n.garment_position = pair_of(stats.garment_position);
  n.garment_velocity = pair_of(stats.garment_velocity);
  n.garment_acceleration = pair_of(stats.garment_acceleration);
  n.body_position = pair_of(stats.body_position);
  n.body_velocity = pair_of(stats.body_velocity);
  n.body_acceleration = pair_of(stats.body_acceleration);
  return n;
}

Normalization Normalization::to(const at::Device& device) const {
  return map_pairs(*this, [&](const NormPair& p) { return NormPair{p.mean.to(device), p.std.to(device)}; });
}

}  // namespace layers::zoo
