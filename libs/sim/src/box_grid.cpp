// BoxGrid::build (see box_grid.h): two passes of a counting sort over the
// cells each box overlaps.
#include "box_grid.h"

#include <algorithm>

namespace layers::sim::detail {

bool BoxGrid::cells_of(const Box& b, std::int64_t lo[3], std::int64_t hi[3]) const {
  for (int k = 0; k < 3; ++k) {
    const double a = b.lo[k] * inv_cell_, z = b.hi[k] * inv_cell_;
    // Beyond any scene (or NaN): treated as wider than the span.
    if (!(a > -1e15 && z < 1e15 && z - a < kMaxSpan + 1)) return false;
    lo[k] = cell_coord(b.lo[k], inv_cell_);
    hi[k] = cell_coord(b.hi[k], inv_cell_);
    if (hi[k] - lo[k] >= kMaxSpan) return false;
  }
  return true;
}

void BoxGrid::build(const std::vector<Box>& boxes, double cell, int first, int count) {
  boxes_ = &boxes;
  first_ = first;
  end_ = count < 0 ? static_cast<int>(boxes.size()) : first + count;
  const auto n = static_cast<std::size_t>(end_ - first_);
  inv_cell_ = 1.0 / cell;
  std::uint64_t size = 64;
  while (size < 4 * n) size *= 2;
  mask_ = size - 1;
  start_.assign(size + 2, 0);
  wide_.clear();
  filed_.assign(n, 0);
  if (seen_.size() != n) {
    seen_.assign(n, 0u);
    stamp_ = 0;
  }
  bounds_ = Box{Vec3::Constant(1e300), Vec3::Constant(-1e300)};
  std::int64_t lo[3], hi[3];
  const auto each_slot = [&](const Box& b, auto&& f) {
    for (std::int64_t ix = lo[0]; ix <= hi[0]; ++ix)
      for (std::int64_t iy = lo[1]; iy <= hi[1]; ++iy)
        for (std::int64_t iz = lo[2]; iz <= hi[2]; ++iz) f(cell_slot(ix, iy, iz, mask_));
    (void)b;
  };
  for (int i = first_; i < end_; ++i) {
    const Box& b = boxes[i];
    if (!b.lo.allFinite() || !b.hi.allFinite()) continue;
    filed_[i - first_] = 1;
    bounds_.lo = bounds_.lo.cwiseMin(b.lo);
    bounds_.hi = bounds_.hi.cwiseMax(b.hi);
    if (!cells_of(b, lo, hi)) {
      wide_.push_back(i);
      continue;
    }
    each_slot(b, [&](std::uint32_t s) { ++start_[s + 1]; });
  }
  for (std::uint64_t s = 0; s <= size; ++s) start_[s + 1] += start_[s];
  entries_.resize(start_[size]);
  for (int i = first_; i < end_; ++i) {
    const Box& b = boxes[i];
    if (!filed_[i - first_] || !cells_of(b, lo, hi)) continue;
    each_slot(b, [&](std::uint32_t s) { entries_[start_[s]++] = i; });
  }
  for (std::uint64_t s = size; s > 0; --s) start_[s] = start_[s - 1];
  start_[0] = 0;
}

}  // namespace layers::sim::detail
