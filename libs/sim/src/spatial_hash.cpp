// SpatialHash::build (see spatial_hash.h).
#include "spatial_hash.h"

namespace layers::sim::detail {

void SpatialHash::build(const Vec3s& points, double cell) {
  cell_ = cell;
  inv_cell_ = 1.0 / cell;
  std::uint64_t size = 64;
  while (size < 2 * points.size()) size *= 2;
  mask_ = size - 1;
  start_.assign(size + 2, 0);
  slots_.resize(points.size());
  const std::uint32_t none = static_cast<std::uint32_t>(size);
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec3& p = points[i];
    if (!std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) {
      slots_[i] = none;
      continue;
    }
    slots_[i] = slot(coord(p.x()), coord(p.y()), coord(p.z()));
    ++start_[slots_[i] + 1];
  }
  for (std::uint64_t s = 0; s <= size; ++s) start_[s + 1] += start_[s];
  entries_.resize(start_[size]);
  // start_[s] is used as the fill cursor of slot s, then restored.
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (slots_[i] != none) entries_[start_[slots_[i]]++] = static_cast<int>(i);
  }
  for (std::uint64_t s = size; s > 0; --s) start_[s] = start_[s - 1];
  start_[0] = 0;
}

}  // namespace layers::sim::detail
