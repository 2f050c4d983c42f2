// box_grid.h (internal) -- the broad phase of the continuous-collision pass:
// axis-aligned boxes (the swept boxes of vertices, edges and faces over a
// substep) filed under every cell of a uniform grid they overlap, the
// cells hashed into a table (cell_slot, as every grid of the solver).
// A box spanning more than kMaxSpan cells along an axis (a wild motion) is
// kept on a list that every query scans. A grid may file a range of a box
// array (one cloth's features); a query outside the bounds of what it
// filed costs one box test. Queries report each filed box
// that overlaps theirs once, in a fixed order: the same inputs give the
// same pairs in the same order.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include "layers/sim/cloth.h"
#include "spatial_hash.h"

namespace layers::sim::detail {

struct Box {
  Vec3 lo, hi;
  bool overlaps(const Box& o) const { return (lo.array() <= o.hi.array()).all() && (o.lo.array() <= hi.array()).all(); }
};

class BoxGrid {
 public:
  // Files boxes[i] for every i in [first, first + count) (all of them
  // when count < 0); non-finite boxes are left out. Queries report the
  // indices into `boxes`.
  void build(const std::vector<Box>& boxes, double cell, int first = 0, int count = -1);
  // Calls f(i) once for every filed box i that overlaps `query`.
  template <class F>
  void visit(const Box& query, F&& f) const {
    if (boxes_ == nullptr || !query.lo.allFinite() || !query.hi.allFinite() || !bounds_.overlaps(query)) return;
    if (++stamp_ == 0) {
      std::fill(seen_.begin(), seen_.end(), 0u);
      stamp_ = 1;
    }
    const auto take = [&](int i) {
      if (seen_[i - first_] == stamp_) return;
      seen_[i - first_] = stamp_;
      if ((*boxes_)[i].overlaps(query)) f(i);
    };
    for (int i : wide_) take(i);
    std::int64_t lo[3], hi[3];
    if (!cells_of(query, lo, hi)) {
      // A query wider than the grid's span: every filed box.
      for (int i = first_; i < end_; ++i) {
        if (filed_[i - first_]) take(i);
      }
      return;
    }
    for (std::int64_t ix = lo[0]; ix <= hi[0]; ++ix)
      for (std::int64_t iy = lo[1]; iy <= hi[1]; ++iy)
        for (std::int64_t iz = lo[2]; iz <= hi[2]; ++iz) {
          const std::uint32_t s = cell_slot(ix, iy, iz, mask_);
          for (int e = start_[s]; e < start_[s + 1]; ++e) take(entries_[e]);
        }
  }

  static constexpr int kMaxSpan = 8;

 private:
  // The cell range of a box; false when it spans more than kMaxSpan cells.
  bool cells_of(const Box& b, std::int64_t lo[3], std::int64_t hi[3]) const;

  const std::vector<Box>* boxes_ = nullptr;
  int first_ = 0, end_ = 0;                 // the filed range of *boxes_
  Box bounds_{Vec3::Zero(), Vec3::Zero()};  // of every filed box (empty: inverted)
  double inv_cell_ = 1;
  std::uint64_t mask_ = 0;
  std::vector<int> start_, entries_, wide_;
  std::vector<char> filed_;
  mutable std::vector<std::uint32_t> seen_;
  mutable std::uint32_t stamp_ = 0;
};

}  // namespace layers::sim::detail
