// Midpoint subdivision (see subdivide.h).
#include "layers/geometry/subdivide.h"

#include <map>
#include <string>

#include "layers/core/error.h"

namespace layers::geometry {

Subdivision subdivide(const std::vector<std::int32_t>& faces, std::int64_t vertices) {
  Subdivision s;
  s.old_vertices = vertices;
  std::map<std::pair<std::int32_t, std::int32_t>, std::int32_t> edge_vertex;
  const auto midpoint = [&](std::int32_t a, std::int32_t b) {
    const std::pair<std::int32_t, std::int32_t> key = a < b ? std::make_pair(a, b) : std::make_pair(b, a);
    auto [it, added] = edge_vertex.emplace(key, static_cast<std::int32_t>(s.vertices()));
    if (added) s.midpoints.push_back(key);
    return it->second;
  };
  for (std::size_t f = 0; f + 2 < faces.size(); f += 3) {
    const std::int32_t a = faces[f], b = faces[f + 1], c = faces[f + 2];
    for (std::int32_t v : {a, b, c})
      if (v < 0 || v >= vertices)
        throw InputError("subdivide", "faces", "indices in [0, " + std::to_string(vertices) + ")", std::to_string(v));
    const std::int32_t ab = midpoint(a, b), bc = midpoint(b, c), ca = midpoint(c, a);
    s.faces.insert(s.faces.end(), {a, ab, ca, ab, b, bc, ca, bc, c, ab, bc, ca});
  }
  return s;
}

std::vector<float> Subdivision::apply(const std::vector<float>& values, int width) const {
  const std::size_t block = static_cast<std::size_t>(old_vertices) * static_cast<std::size_t>(width);
  if (block == 0 || values.size() % block != 0)
    throw Error("Subdivision::apply: " + std::to_string(values.size()) + " values are not blocks of " +
                std::to_string(old_vertices) + " rows of " + std::to_string(width));
  const std::size_t w = static_cast<std::size_t>(width);
  std::vector<float> out;
  out.reserve(values.size() / block * static_cast<std::size_t>(vertices()) * w);
  for (std::size_t start = 0; start < values.size(); start += block) {
    const float* in = values.data() + start;
    out.insert(out.end(), in, in + block);
    for (const auto& [a, b] : midpoints)
      for (std::size_t k = 0; k < w; ++k) out.push_back(0.5f * (in[a * w + k] + in[b * w + k]));
  }
  return out;
}

}  // namespace layers::geometry
