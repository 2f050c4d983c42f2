// UV points, bilinear splat weights, splat and sample (see uv_splat.h).
#include "layers/mgnet/uv_splat.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "layers/core/error.h"

namespace layers::mgnet {
namespace {

struct UvPoint {
  std::int64_t vertex;
  float u, v;
  bool operator<(const UvPoint& o) const { return std::tie(vertex, u, v) < std::tie(o.vertex, o.u, o.v); }
  bool operator==(const UvPoint& o) const { return vertex == o.vertex && u == o.u && v == o.v; }
};

// Distinct (vertex, UV value) pairs among the face corners, sorted.
std::vector<UvPoint> uv_points(const zoo::GarmentStatic& g) {
  const at::Tensor faces = g.faces.to(at::kCPU, at::kLong).contiguous();
  const at::Tensor uv_faces = g.uv_faces.to(at::kCPU, at::kLong).contiguous();
  const at::Tensor uv = g.uv.to(at::kCPU, at::kFloat).contiguous();
  const auto f = faces.accessor<std::int64_t, 2>();
  const auto fu = uv_faces.accessor<std::int64_t, 2>();
  const auto t = uv.accessor<float, 2>();
  std::vector<UvPoint> points;
  points.reserve(static_cast<std::size_t>(3 * faces.size(0)));
  for (std::int64_t i = 0; i < faces.size(0); ++i)
    for (int c = 0; c < 3; ++c) points.push_back({f[i][c], t[fu[i][c]][0], t[fu[i][c]][1]});
  std::sort(points.begin(), points.end());
  points.erase(std::unique(points.begin(), points.end()), points.end());
  return points;
}

struct Range {
  float lo = INFINITY, hi = -INFINITY;
  void add(float x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  bool usable() const { return std::isfinite(lo) && std::isfinite(hi) && hi > lo; }
  std::string text() const {
    std::ostringstream out;
    out << "[" << lo << ", " << hi << "]";
    return out.str();
  }
};

}  // namespace

UvSplat garment_splat(const zoo::GarmentStatic& g, std::int64_t resolution, const std::string& where) {
  if (resolution < 2) throw Error("mgnet: UV image resolution must be at least 2, got " + std::to_string(resolution));
  const std::vector<UvPoint> points = uv_points(g);
  Range ru, rv;
  for (const UvPoint& p : points) {
    ru.add(p.u);
    rv.add(p.v);
  }
  if (!ru.usable() || !rv.usable()) {
    throw InputError(where, "uv", "face UVs spanning a non-zero range along both u and v",
                     points.empty() ? std::string("no faces") : "u in " + ru.text() + ", v in " + rv.text());
  }
  const std::int64_t n = static_cast<std::int64_t>(points.size()), R = resolution;
  at::Tensor uv = at::empty({n, 2}, at::kFloat), vertex = at::empty({n}, at::kLong);
  at::Tensor pixel = at::empty({n, 4}, at::kLong), weight = at::empty({n, 4}, at::kFloat);
  auto uv_a = uv.accessor<float, 2>();
  auto vertex_a = vertex.accessor<std::int64_t, 1>();
  auto pixel_a = pixel.accessor<std::int64_t, 2>();
  auto weight_a = weight.accessor<float, 2>();
  const float scale = static_cast<float>(R - 1);
  for (std::int64_t i = 0; i < n; ++i) {
    const UvPoint& p = points[static_cast<std::size_t>(i)];
    const float u = (p.u - ru.lo) / (ru.hi - ru.lo), v = (p.v - rv.lo) / (rv.hi - rv.lo);
    uv_a[i][0] = u;
    uv_a[i][1] = v;
    vertex_a[i] = p.vertex;
    const float x = u * scale, y = v * scale;
    const std::int64_t x0 = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(x)), 0, R - 2);
    const std::int64_t y0 = std::clamp<std::int64_t>(static_cast<std::int64_t>(std::floor(y)), 0, R - 2);
    const float fx = x - static_cast<float>(x0), fy = y - static_cast<float>(y0);
    const std::int64_t corner[4] = {y0 * R + x0, y0 * R + x0 + 1, (y0 + 1) * R + x0, (y0 + 1) * R + x0 + 1};
    const float w[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
    for (int k = 0; k < 4; ++k) {
      pixel_a[i][k] = corner[k];
      weight_a[i][k] = w[k];
    }
  }
  UvSplat s;
  s.resolution = R;
  s.images = 1;
  s.vertices = g.rest.size(0);
  const at::Device device = g.uv.device();
  s.uv = uv.to(device);
  s.vertex = vertex.to(device);
  s.pixel = pixel.to(device);
  s.weight = weight.to(device);
  s.weight_sum = at::zeros({R * R}, s.weight.options()).index_add(0, s.pixel.reshape(-1), s.weight.reshape(-1));
  s.points_per_vertex = at::bincount(s.vertex, {}, s.vertices).to(at::kFloat);
  return s;
}

UvSplat concatenate(const std::vector<UvSplat>& parts) {
  UvSplat out;
  if (parts.empty()) return out;
  out.resolution = parts.front().resolution;
  const std::int64_t area = out.resolution * out.resolution;
  std::vector<at::Tensor> uv, vertex, pixel, weight, weight_sum, count;
  for (const UvSplat& p : parts) {
    if (p.resolution != out.resolution) throw Error("mgnet: UV splats of different resolutions concatenated");
    uv.push_back(p.uv);
    vertex.push_back(p.vertex + out.vertices);
    pixel.push_back(p.pixel + out.images * area);
    weight.push_back(p.weight);
    weight_sum.push_back(p.weight_sum);
    count.push_back(p.points_per_vertex);
    out.images += p.images;
    out.vertices += p.vertices;
  }
  out.uv = at::cat(uv);
  out.vertex = at::cat(vertex);
  out.pixel = at::cat(pixel);
  out.weight = at::cat(weight);
  out.weight_sum = at::cat(weight_sum);
  out.points_per_vertex = at::cat(count);
  return out;
}

at::Tensor splat(const UvSplat& s, const at::Tensor& features) {
  const std::int64_t R = s.resolution, C = features.size(1), P = s.vertex.size(0);
  const at::Tensor at_points = features.index_select(0, s.vertex);  // [P,C]
  const at::Tensor weighted = (at_points.unsqueeze(1) * s.weight.unsqueeze(-1)).reshape({4 * P, C});
  const at::Tensor sum =
      at::zeros({s.images * R * R, C}, features.options()).index_add(0, s.pixel.reshape(-1), weighted);
  const at::Tensor denom = at::where(s.weight_sum > 0, s.weight_sum, at::ones_like(s.weight_sum));
  return (sum / denom.unsqueeze(1)).reshape({s.images, R, R, C}).permute({0, 3, 1, 2}).contiguous();
}

at::Tensor coverage(const UvSplat& s) {
  return s.weight_sum.clamp_max(1.0).reshape({s.images, 1, s.resolution, s.resolution});
}

at::Tensor sample(const UvSplat& s, const at::Tensor& images) {
  const std::int64_t R = s.resolution, C = images.size(1), P = s.vertex.size(0);
  const at::Tensor flat = images.permute({0, 2, 3, 1}).reshape({s.images * R * R, C});
  const at::Tensor corners = flat.index_select(0, s.pixel.reshape(-1)).reshape({P, 4, C});
  const at::Tensor at_points = (corners * s.weight.unsqueeze(-1)).sum(1);  // [P,C]
  const at::Tensor sum = at::zeros({s.vertices, C}, images.options()).index_add(0, s.vertex, at_points);
  return sum / s.points_per_vertex.clamp_min(1.0).unsqueeze(1);
}

}  // namespace layers::mgnet
