// tests/support/reference_fixture.h -- tiny scenes for the
// reference models (plugins/static/test, plugins/skinned/test): grid garments as SequenceStatic, step inputs, rigid
// transforms (Eigen, double) and their tensor forms.
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

#include "grid_tensor.h"
#include "layers/zoo/model.h"

namespace layers::test {

using Rigid = Eigen::Isometry3d;

inline Rigid rigid(const Eigen::Vector3d& axis, double angle, const Eigen::Vector3d& translation) {
  Rigid t = Rigid::Identity();
  t.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  t.translation() = translation;
  return t;
}

// rows x cols points spaced `spacing` apart in the plane through `origin`
// spanned by x and y, as [rows*cols, 3] float.
inline at::Tensor grid_points(int rows, int cols, double spacing, const Eigen::Vector3d& origin) {
  std::vector<float> v;
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      for (int k = 0; k < 3; ++k) v.push_back(float(origin[k] + (k == 0 ? c * spacing : k == 1 ? r * spacing : 0.0)));
  return at::tensor(v).reshape({rows * cols, 3});
}

// A garment whose rest shape is `rest` (a rows x cols grid).
inline zoo::GarmentStatic grid_garment(const std::string& name, std::int64_t layer, const at::Tensor& rest, int rows,
                                       int cols) {
  zoo::GarmentStatic g;
  g.name = name;
  g.type = layer == 0 ? "jumpsuit" : "jacket";
  g.layer = layer;
  g.faces = grid_faces_tensor(rows, cols, at::kInt);  // int32, as stored in LAYERS-H5
  g.rest = rest;
  g.uv = rest.slice(1, 0, 2).clone();
  g.uv_faces = g.faces.clone();
  g.panel = at::zeros({g.faces.size(0)}, at::kInt);
  g.attributes = at::full({7}, 0.5f);
  return g;
}

// Rows of `points` [N,3] moved by `t`.
inline at::Tensor transformed(const Rigid& t, const at::Tensor& points) {
  at::Tensor r = at::empty({3, 3}, at::kDouble), p = at::empty({3}, at::kDouble);
  for (int i = 0; i < 3; ++i) {
    p[i] = t.translation()[i];
    for (int j = 0; j < 3; ++j) r[i][j] = t.linear()(i, j);
  }
  return (at::matmul(points.to(at::kDouble), r.t()) + p).to(points.scalar_type());
}

// A step input with zero wind; joints optional.
inline zoo::StepInput step_input(std::vector<zoo::GarmentState> garments, const at::Tensor& body,
                                 const at::Tensor& body_next, const at::Tensor& root, const at::Tensor& root_rot,
                                 const at::Tensor& joints = {}, const at::Tensor& joints_next = {}) {
  zoo::StepInput in;
  in.garments = std::move(garments);
  in.body = body;
  in.body_next = body_next;
  in.root = root;
  in.root_rot = root_rot;
  in.wind_rotation = at::zeros({2, 4});
  in.wind_rotation.select(1, 0).fill_(1.0f);
  in.wind_strength = at::zeros({2});
  in.joints = joints;
  in.joints_next = joints_next;
  return in;
}

}  // namespace layers::test
