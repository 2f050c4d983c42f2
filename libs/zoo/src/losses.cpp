// The shared training losses (see losses.h): position MSE, face-normal loss,
// body and layer collision losses, and differentiable vertex normals.
#include "layers/zoo/losses.h"

#include <ATen/core/grad_mode.h>

#include <cmath>
#include <sstream>
#include <string>

#include "layers/core/error.h"
#include "layers/geometry/nearest.h"
#include "layers/geometry/normals.h"

namespace layers::zoo {
namespace {

std::string describe(const at::Tensor& t) {
  if (!t.defined()) return "nothing (undefined tensor)";
  std::ostringstream out;
  out << t.scalar_type() << " tensor " << t.sizes() << " on " << t.device();
  return out.str();
}

[[noreturn]] void fail(const char* loss, const char* arg, const std::string& expected, const std::string& got) {
  throw Error(std::string(loss) + ": " + arg + ": expected " + expected + ", got " + got);
}

// [N,3] floating-point positions.
void check_points(const char* loss, const char* arg, const at::Tensor& t) {
  if (!t.defined() || t.dim() != 2 || t.size(1) != 3 || !at::isFloatingType(t.scalar_type()))
    fail(loss, arg, "a floating-point tensor [*, 3]", describe(t));
}

void check_same_device(const char* loss, const char* arg, const at::Tensor& t, const at::Tensor& like) {
  if (t.device() != like.device()) {
    std::ostringstream expected;
    expected << "a tensor on " << like.device();
    fail(loss, arg, expected.str(), describe(t));
  }
}

// [F,3] integer faces into `vertices` rows, as int64 on the vertices' device.
at::Tensor checked_faces(const char* loss, const char* arg, const at::Tensor& faces, const at::Tensor& vertices) {
  if (!faces.defined() || faces.dim() != 2 || faces.size(1) != 3 ||
      !at::isIntegralType(faces.scalar_type(), /*includeBool=*/false))
    fail(loss, arg, "an integer tensor [*, 3]", describe(faces));
  at::Tensor out = faces.to(vertices.device(), at::kLong);
  if (out.numel() > 0) {
    const std::int64_t lo = out.min().item<std::int64_t>(), hi = out.max().item<std::int64_t>();
    if (lo < 0 || hi >= vertices.size(0)) {
      fail(loss, arg, "indices in [0, " + std::to_string(vertices.size(0)) + ")",
           "values in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    }
  }
  return out;
}

// Rows scaled to unit length; zero rows stay zero with a zero gradient
// (dividing by a clamped length instead would give them gradients of
// 1/clamp). The length is replaced by 1 where it is 0 so that no NaN
// reaches the masked-out branch's backward.
at::Tensor unit_rows(const at::Tensor& v) {
  at::Tensor length = v.norm(2, {1}, /*keepdim=*/true);
  at::Tensor nonzero = length > 0;
  return at::where(nonzero, v / at::where(nonzero, length, at::ones_like(length)), at::zeros_like(v));
}

// Cross product of the two edges leaving each face's first corner: the face
// normal scaled by twice the face area. faces: int64 [F,3].
at::Tensor doubled_area_normals(const at::Tensor& vertices, const at::Tensor& faces) {
  at::Tensor a = vertices.index_select(0, faces.select(1, 0));
  at::Tensor b = vertices.index_select(0, faces.select(1, 1));
  at::Tensor c = vertices.index_select(0, faces.select(1, 2));
  return at::cross(b - a, c - a, 1);
}

// One scatter_add over all corners (the CPU index_add of 1.13 loops over
// rows: ~7x slower on a 26k-face body).
at::Tensor area_weighted_normals(const at::Tensor& vertices, const at::Tensor& faces) {
  at::Tensor n = doubled_area_normals(vertices, faces);
  at::Tensor corners = faces.reshape({-1, 1}).expand({-1, 3});
  at::Tensor sum = at::zeros_like(vertices).scatter_add(0, corners, n.unsqueeze(1).expand({-1, 3, 3}).reshape({-1, 3}));
  return unit_rows(sum);
}

// A detached float32 CPU copy of [N,3] positions as geometry points.
geometry::Points cpu_points(const at::Tensor& t) {
  at::Tensor cpu = t.detach().to(at::kCPU, at::kFloat).contiguous();
  return Eigen::Map<const geometry::Points>(cpu.data_ptr<float>(), cpu.size(0), 3);
}

// The nearest surface vertex of each point (k-d tree on CPU copies) and
// that vertex's unit normal, both as rows on the points' device. A
// non-finite point gets vertex 0 (its loss term is then non-finite too).
struct Nearest {
  at::Tensor index;    // [N] int64
  at::Tensor normals;  // [N,3]
};

Nearest nearest_on_surface(const char* loss, const char* surface_arg, const at::Tensor& points,
                           const at::Tensor& surface, const at::Tensor& faces) {
  geometry::Points surface_cpu = cpu_points(surface);
  if (!surface_cpu.allFinite()) fail(loss, surface_arg, "finite positions", "NaN or infinity");
  const geometry::PointIndex tree(surface_cpu);
  Eigen::VectorXi nearest = tree.nearest_all(cpu_points(points)).cwiseMax(0);
  Nearest out;
  out.index = at::from_blob(nearest.data(), {nearest.size()}, at::kInt).to(at::kLong).to(points.device());
  if (at::GradMode::is_enabled() && surface.requires_grad()) {
    // Differentiable normals (the layer loss moves the inner layer too).
    out.normals = area_weighted_normals(surface, faces).index_select(0, out.index);
    return out;
  }
  // A constant surface (the body): the same normals from layers::geometry
  // on the CPU copy, ~10x cheaper than torch's scatter on a 13k-vertex
  // body, and only the rows needed go back to the device.
  at::Tensor faces_cpu = faces.to(at::kCPU, at::kInt).contiguous();
  const geometry::Points all = geometry::vertex_normals(
      surface_cpu, Eigen::Map<const geometry::Faces>(faces_cpu.data_ptr<int>(), faces_cpu.size(0), 3));
  geometry::Points picked(nearest.size(), 3);
  for (Eigen::Index i = 0; i < nearest.size(); ++i) picked.row(i) = all.row(nearest(i));
  out.normals = at::from_blob(picked.data(), {picked.rows(), 3}, at::kFloat)
                    .to(surface.device(), surface.scalar_type(), /*non_blocking=*/false, /*copy=*/true);
  return out;
}

// The collision term shared by the body and layer losses: points against
// the surface of (surface, faces), see losses.h.
at::Tensor surface_penalty(const char* loss, const char* points_arg, const char* surface_arg, const char* faces_arg,
                           const at::Tensor& points, const at::Tensor& surface, const at::Tensor& faces, double eps) {
  check_points(loss, points_arg, points);
  check_points(loss, surface_arg, surface);
  check_same_device(loss, surface_arg, surface, points);
  at::Tensor f = checked_faces(loss, faces_arg, faces, surface);
  if (!std::isfinite(eps)) fail(loss, "eps", "a finite distance", std::to_string(eps));
  if (points.size(0) == 0 || surface.size(0) == 0) return (points.sum() + surface.sum()) * 0;

  const Nearest nearest = nearest_on_surface(loss, surface_arg, points, surface, f);
  at::Tensor h = surface.index_select(0, nearest.index);
  at::Tensor d = ((points - h) * nearest.normals).sum(1);
  at::Tensor violating = (d < eps).sum().clamp_min(1).to(d.scalar_type());
  return (eps - d).clamp_min(0).pow(2).sum() / violating;
}

// The arguments of a normal loss, checked: pred and truth of one shape on
// one device, and at least one face; returns the faces as int64.
at::Tensor checked_normal_inputs(const char* loss, const at::Tensor& pred, const at::Tensor& truth,
                                 const at::Tensor& faces) {
  check_points(loss, "pred", pred);
  check_points(loss, "truth", truth);
  check_same_device(loss, "truth", truth, pred);
  if (truth.size(0) != pred.size(0)) fail(loss, "truth", "the same shape as pred " + describe(pred), describe(truth));
  at::Tensor f = checked_faces(loss, "faces", faces, pred);
  if (f.size(0) == 0) fail(loss, "faces", "at least one face", "none");
  return f;
}

}  // namespace

at::Tensor position_mse(const at::Tensor& pred, const at::Tensor& truth) {
  constexpr const char* loss = "position_mse";
  check_points(loss, "pred", pred);
  check_points(loss, "truth", truth);
  check_same_device(loss, "truth", truth, pred);
  if (truth.size(0) != pred.size(0)) fail(loss, "truth", "the same shape as pred " + describe(pred), describe(truth));
  if (pred.size(0) == 0) fail(loss, "pred", "at least one vertex", "none");
  return (pred - truth).pow(2).sum(1).mean();
}

at::Tensor normal_loss(const at::Tensor& pred, const at::Tensor& truth, const at::Tensor& faces) {
  const at::Tensor f = checked_normal_inputs("normal_loss", pred, truth, faces);
  at::Tensor n_pred = unit_rows(doubled_area_normals(pred, f));
  at::Tensor n_truth = unit_rows(doubled_area_normals(truth, f));
  return (n_pred - n_truth).pow(2).sum(1).mean();
}

at::Tensor vertex_normal_loss(const at::Tensor& pred, const at::Tensor& truth, const at::Tensor& faces) {
  const at::Tensor f = checked_normal_inputs("vertex_normal_loss", pred, truth, faces);
  return (area_weighted_normals(pred, f) - area_weighted_normals(truth, f)).pow(2).sum(1).mean();
}

at::Tensor body_collision_loss(const at::Tensor& garment, const at::Tensor& body, const at::Tensor& body_faces,
                               double eps) {
  return surface_penalty("body_collision_loss", "garment", "body", "body_faces", garment, body, body_faces, eps);
}

at::Tensor layer_collision_loss(const at::Tensor& outer, const at::Tensor& inner, const at::Tensor& inner_faces,
                                double eps) {
  return surface_penalty("layer_collision_loss", "outer", "inner", "inner_faces", outer, inner, inner_faces, eps);
}

at::Tensor vertex_normals(const at::Tensor& vertices, const at::Tensor& faces) {
  constexpr const char* loss = "vertex_normals";
  check_points(loss, "vertices", vertices);
  return area_weighted_normals(vertices, checked_faces(loss, "faces", faces, vertices));
}

}  // namespace layers::zoo
