// spatial_hash.h (internal) -- a uniform grid hashed into a table, rebuilt
// from scratch whenever the points move (counting sort: O(n), no
// allocation once warm). Within a slot, points keep their index order, so
// visiting is deterministic. Two cells may share a slot: callers filter by
// distance, and nearest-point searches are unaffected by repeats.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include "layers/sim/cloth.h"

namespace layers::sim::detail {

// The cell index floor(v * inv_cell) of a coordinate (|v * inv_cell| below
// 2^53), without a call into libm; every grid of the solver finds its
// cells with this.
inline std::int64_t cell_coord(double v, double inv_cell) {
  const double y = v * inv_cell;
  const auto i = static_cast<std::int64_t>(y);
  return i - (y < static_cast<double>(i) ? 1 : 0);
}

// The table slot of grid cell (ix, iy, iz) in a table of mask + 1 slots (a
// power of two); every grid of the solver hashes its cells with this.
inline std::uint32_t cell_slot(std::int64_t ix, std::int64_t iy, std::int64_t iz, std::uint64_t mask) {
  const std::uint64_t h = static_cast<std::uint64_t>(ix) * 73856093ULL ^ static_cast<std::uint64_t>(iy) * 19349663ULL ^
                          static_cast<std::uint64_t>(iz) * 83492791ULL;
  return static_cast<std::uint32_t>(h & mask);
}

class SpatialHash {
 public:
  // Indexes `points` with cubic cells of side `cell` (> 0). Non-finite
  // points are left out.
  void build(const Vec3s& points, double cell);
  double cell() const { return cell_; }

  // Calls f(index) for every point in the cells overlapping the cube of
  // half-side `radius` around p.
  template <class F>
  void visit(const Vec3& p, double radius, F&& f) const {
    if (entries_.empty() || !std::isfinite(p.x()) || !std::isfinite(p.y()) || !std::isfinite(p.z())) return;
    const std::int64_t x0 = coord(p.x() - radius), x1 = coord(p.x() + radius);
    const std::int64_t y0 = coord(p.y() - radius), y1 = coord(p.y() + radius);
    const std::int64_t z0 = coord(p.z() - radius), z1 = coord(p.z() + radius);
    for (std::int64_t ix = x0; ix <= x1; ++ix)
      for (std::int64_t iy = y0; iy <= y1; ++iy)
        for (std::int64_t iz = z0; iz <= z1; ++iz) {
          const std::uint32_t s = slot(ix, iy, iz);
          for (int e = start_[s]; e < start_[s + 1]; ++e) f(entries_[e]);
        }
  }

 private:
  std::int64_t coord(double v) const { return cell_coord(v, inv_cell_); }
  std::uint32_t slot(std::int64_t ix, std::int64_t iy, std::int64_t iz) const { return cell_slot(ix, iy, iz, mask_); }

  double cell_ = 1, inv_cell_ = 1;
  std::uint64_t mask_ = 0;
  std::vector<int> start_;            // mask_ + 2 entries
  std::vector<int> entries_;          // point indices grouped by slot
  std::vector<std::uint32_t> slots_;  // scratch: slot per point (mask_ + 1: left out)
};

}  // namespace layers::sim::detail
