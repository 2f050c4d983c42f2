// layers/geometry/subdivide.h -- midpoint subdivision of a triangle mesh:
// every triangle splits into four through its edge midpoints, so the
// vertex count grows about 4x per level while the surface stays the same.
// The result says how every new vertex is made (the mean of two old ones),
// so any per-vertex array (positions of every frame, UVs) follows with
// apply(). Used to scale real scenes for benchmarks.
#pragma once

#include <cstdint>
#include <utility>
#include <vector>

namespace layers::geometry {

struct Subdivision {
  std::int64_t old_vertices = 0;
  std::vector<std::pair<std::int32_t, std::int32_t>> midpoints;  // new vertex old_vertices + i = mean of the pair
  std::vector<std::int32_t> faces;                               // [4F,3]

  std::int64_t vertices() const { return old_vertices + static_cast<std::int64_t>(midpoints.size()); }
  // Extends `values` (rows of `width` floats, one per old vertex; several
  // blocks of old_vertices rows, e.g. frames, are handled one after the
  // other) with the midpoint rows.
  std::vector<float> apply(const std::vector<float>& values, int width) const;
};

// `faces` are [F,3] indices into `vertices` vertices; InputError for an
// index out of range.
Subdivision subdivide(const std::vector<std::int32_t>& faces, std::int64_t vertices);

}  // namespace layers::geometry
