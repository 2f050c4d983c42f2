// Tangent frames from positions and fixed per-face UV coefficients (see
// tangent_frames.h).
#include "layers/mgnet/tangent_frames.h"

namespace layers::mgnet {
namespace {

// Below this length a summed normal or tangent counts as vanishing.
constexpr double kTiny = 1e-12;

at::Tensor unit(const at::Tensor& x) { return x / x.norm(2, -1, true).clamp_min(kTiny); }

// Rows of `fallback` where the rows of `x` are shorter than kTiny.
at::Tensor or_else(const at::Tensor& x, const at::Tensor& fallback) {
  return at::where(x.norm(2, -1, true) > kTiny, x, fallback);
}

}  // namespace

TangentBasis tangent_basis(const at::Tensor& faces, const at::Tensor& uv_faces, const at::Tensor& uv,
                           std::int64_t vertices) {
  TangentBasis b;
  b.vertices = vertices;
  b.faces = faces.to(at::kLong);
  const at::Tensor corners =
      uv.to(faces.device(), at::kFloat).index_select(0, uv_faces.to(at::kLong).reshape(-1)).reshape({-1, 3, 2});
  const at::Tensor d1 = corners.select(1, 1) - corners.select(1, 0);
  const at::Tensor d2 = corners.select(1, 2) - corners.select(1, 0);
  const at::Tensor det = d1.select(1, 0) * d2.select(1, 1) - d2.select(1, 0) * d1.select(1, 1);
  const at::Tensor sign = at::sign(det);  // 0 for a degenerate UV triangle
  b.coeff = at::stack({sign * d2.select(1, 1), -sign * d1.select(1, 1)}, 1);
  return b;
}

TangentBasis concatenate(const std::vector<TangentBasis>& parts) {
  TangentBasis out;
  std::vector<at::Tensor> faces, coeff;
  for (const TangentBasis& p : parts) {
    faces.push_back(p.faces + out.vertices);
    coeff.push_back(p.coeff);
    out.vertices += p.vertices;
  }
  if (!parts.empty()) {
    out.faces = at::cat(faces);
    out.coeff = at::cat(coeff);
  }
  return out;
}

at::Tensor vertex_frames(const TangentBasis& basis, const at::Tensor& positions) {
  const at::Tensor p = positions.index_select(0, basis.faces.reshape(-1)).reshape({-1, 3, 3});
  const at::Tensor e1 = p.select(1, 1) - p.select(1, 0), e2 = p.select(1, 2) - p.select(1, 0);
  const at::Tensor face_normal = at::cross(e1, e2, 1);  // length = 2 x area
  const at::Tensor face_tangent =
      basis.coeff.select(1, 0).unsqueeze(1) * e1 + basis.coeff.select(1, 1).unsqueeze(1) * e2;
  const at::Tensor corner_vertex = basis.faces.reshape(-1);
  const auto to_vertices = [&](const at::Tensor& per_face) {
    return at::zeros({basis.vertices, 3}, positions.options())
        .index_add(0, corner_vertex, per_face.repeat_interleave(3, 0));
  };
  const auto axis_of = [&](float x, float y, float z) {
    return at::tensor({x, y, z}, positions.options()).reshape({1, 3});
  };
  const at::Tensor n = unit(or_else(to_vertices(face_normal), axis_of(0, 1, 0).expand({basis.vertices, 3})));

  // Fallback tangent: x unless n is mostly along x, then z.
  const at::Tensor x_axis = axis_of(1, 0, 0), z_axis = axis_of(0, 0, 1);
  const at::Tensor axis = at::where(n.select(1, 0).abs().unsqueeze(1) < 0.9, x_axis, z_axis);
  const auto across = [&](const at::Tensor& v) { return v - (v * n).sum(1, true) * n; };
  const at::Tensor t = unit(or_else(across(to_vertices(face_tangent)), across(axis)));
  const at::Tensor b = at::cross(n, t, 1);
  return at::stack({t, b, n}, 1);
}

at::Tensor to_frame(const at::Tensor& frames, const at::Tensor& d) { return (frames * d.unsqueeze(1)).sum(2); }

at::Tensor from_frame(const at::Tensor& frames, const at::Tensor& local) {
  return (frames * local.unsqueeze(2)).sum(1);
}

}  // namespace layers::mgnet
