// Front orthographic views of meshes as shaded polygons (see mesh_view.h).
#include "layers/report/mesh_view.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "layers/core/error.h"

namespace layers::report {

void ScreenBounds::add(double x, double y) {
  if (empty) {
    xmin = xmax = x, ymin = ymax = y, empty = false;
    return;
  }
  xmin = std::min(xmin, x), xmax = std::max(xmax, x), ymin = std::min(ymin, y), ymax = std::max(ymax, y);
}

void ScreenBounds::add(const ScreenBounds& other) {
  if (other.empty) return;
  add(other.xmin, other.ymin);
  add(other.xmax, other.ymax);
}

std::uint32_t shade(std::uint32_t base_rgb, double nz, double ambient) {
  const double k = ambient + (1.0 - ambient) * std::min(1.0, std::fabs(nz));
  std::uint32_t out = 0;
  for (int shift : {16, 8, 0}) {
    const double c = static_cast<double>((base_rgb >> shift) & 0xffu) * k;
    out |= static_cast<std::uint32_t>(std::lround(std::clamp(c, 0.0, 255.0))) << shift;
  }
  return out;
}

void add_mesh(std::vector<ScreenTriangle>& out, const float* p, std::int64_t n_vertices,
              const std::vector<std::int32_t>& faces, std::uint32_t base_rgb, bool cull_back, float depth_bias) {
  for (std::size_t f = 0; f + 2 < faces.size(); f += 3) {
    const float* v[3];
    bool finite = true;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t i = faces[f + k];
      if (i < 0 || i >= n_vertices)
        throw Error("mesh face " + std::to_string(f / 3) + " names vertex " + std::to_string(i) + " of " +
                    std::to_string(n_vertices));
      v[k] = p + 3 * static_cast<std::size_t>(i);
      finite = finite && std::isfinite(v[k][0]) && std::isfinite(v[k][1]) && std::isfinite(v[k][2]);
    }
    if (!finite) continue;
    const double a[3] = {v[1][0] - v[0][0], v[1][1] - v[0][1], v[1][2] - v[0][2]};
    const double b[3] = {v[2][0] - v[0][0], v[2][1] - v[0][1], v[2][2] - v[0][2]};
    const double n[3] = {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    const double len = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0)) continue;
    const double nz = n[2] / len;
    if (cull_back && nz <= 0) continue;
    ScreenTriangle t;
    for (int k = 0; k < 3; ++k) t.x[k] = v[k][0], t.y[k] = v[k][1];
    t.depth = (v[0][2] + v[1][2] + v[2][2]) / 3.0f + depth_bias;
    t.rgb = shade(base_rgb, nz);
    out.push_back(t);
  }
}

ScreenBounds mesh_bounds(const float* p, std::int64_t n_vertices) {
  ScreenBounds b;
  for (std::int64_t i = 0; i < n_vertices; ++i) {
    const float* v = p + 3 * i;
    if (std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2])) b.add(v[0], v[1]);
  }
  return b;
}

std::string polygon_data(std::vector<ScreenTriangle> triangles) {
  std::stable_sort(triangles.begin(), triangles.end(),
                   [](const ScreenTriangle& a, const ScreenTriangle& b) { return a.depth < b.depth; });
  std::string out;
  out.reserve(triangles.size() * 80);
  char line[96];
  for (const ScreenTriangle& t : triangles) {
    for (int k = 0; k < 3; ++k) {
      std::snprintf(line, sizeof line, "%.4f %.4f %u\n", t.x[k], t.y[k], static_cast<unsigned>(t.rgb));
      out += line;
    }
    out += '\n';
  }
  return out;
}

}  // namespace layers::report
