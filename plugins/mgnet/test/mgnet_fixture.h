// plugins/mgnet/test/mgnet_fixture.h -- small synthetic scenes for the MGNet
// tests: grid garments (faces from tests/support/grid.h) (flat or wrapped on an open cylinder) with grid UV
// charts, a cylinder body, and a sequence where the garments ride the
// body root with a travelling radial wave (smooth, so a UV-image model can
// fit it) and wind changes half-way.
#pragma once

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "grid_tensor.h"
#include "layers/zoo/model.h"

namespace layers::mgnet::testing {

// UVs of the grid: column c, row r -> (u0 + su c / (cols-1), v0 + sv r / (rows-1)).
inline at::Tensor grid_uv(std::int64_t rows, std::int64_t cols, float u0 = 0, float v0 = 0, float su = 1,
                          float sv = 1) {
  at::Tensor u = at::linspace(u0, u0 + su, cols).repeat({rows});
  at::Tensor v = at::linspace(v0, v0 + sv, rows).repeat_interleave(cols);
  return at::stack({u, v}, 1);
}

// The grid on an open cylinder around +y (column = angle over 300 degrees,
// row = height), centred at the origin.
inline at::Tensor grid_cylinder(std::int64_t rows, std::int64_t cols, float radius, float height) {
  const at::Tensor angle = at::linspace(0, 5.2359878, cols).repeat({rows});
  const at::Tensor y = at::linspace(-0.5 * height, 0.5 * height, rows).repeat_interleave(cols);
  return at::stack({radius * at::cos(angle), y, -radius * at::sin(angle)}, 1);
}

inline zoo::GarmentStatic grid_garment(const std::string& name, std::int64_t layer, const at::Tensor& rest,
                                       std::int64_t rows, std::int64_t cols) {
  zoo::GarmentStatic g;
  g.name = name;
  g.type = name;
  g.layer = layer;
  g.faces = test::grid_faces_tensor(static_cast<int>(rows), static_cast<int>(cols));
  g.rest = rest;
  g.uv = grid_uv(rows, cols);
  g.uv_faces = g.faces.clone();
  g.panel = at::zeros({g.faces.size(0)}, at::kLong);
  g.attributes = at::full({7}, 0.5f);
  return g;
}

// A scene: body cylinder + garments, and their motion over frames.
struct Scene {
  zoo::SequenceStatic statics;
  at::Tensor body_rest;  // [Vb,3]

  at::Tensor root(std::int64_t t) const {
    const double s = static_cast<double>(t);
    return at::tensor({float(0.02 * s), float(0.9 + 0.01 * std::sin(0.3 * s)), float(0.01 * s)});
  }
  at::Tensor body(std::int64_t t) const { return body_rest + root(t); }
  // Rest shape + root + a radial wave travelling along u (1 cm).
  at::Tensor garment(std::size_t k, std::int64_t t) const {
    const zoo::GarmentStatic& g = statics.garments[k];
    const at::Tensor radial = at::stack({g.rest.select(1, 0), at::zeros({g.rest.size(0)}), g.rest.select(1, 2)}, 1);
    const at::Tensor dir = radial / radial.norm(2, 1, true).clamp_min(1e-6);
    const at::Tensor u = at::atan2(-g.rest.select(1, 2), g.rest.select(1, 0));
    const at::Tensor wave = 0.01 * at::sin(0.5 * static_cast<double>(t) + 2.0 * u + 3.0 * g.rest.select(1, 1));
    return g.rest + wave.unsqueeze(1) * dir + root(t);
  }

  // The step input predicting t+1 from t-1 and t (t >= 1).
  zoo::StepInput input(std::int64_t t) const {
    zoo::StepInput in;
    for (std::size_t k = 0; k < statics.garments.size(); ++k) in.garments.push_back({garment(k, t - 1), garment(k, t)});
    in.body = body(t);
    in.body_next = body(t + 1);
    in.root = at::stack({root(t - 1), root(t), root(t + 1)});
    in.root_rot = at::tensor({1.f, 0.f, 0.f, 0.f}).repeat({3, 1});
    const float s = t < 4 ? 100.f : 300.f;
    in.wind_rotation = at::tensor({0.9238795f, 0.f, 0.3826834f, 0.f}).repeat({2, 1});
    in.wind_strength = at::tensor({s, s});
    return in;
  }
  std::vector<at::Tensor> truth(std::int64_t t) const {
    std::vector<at::Tensor> out;
    for (std::size_t k = 0; k < statics.garments.size(); ++k) out.push_back(garment(k, t + 1));
    return out;
  }
};

// Inner (layer 0) and outer (layer 1) cylinder garments of rows x cols
// around a 8 x 16 body cylinder.
inline Scene two_garment_scene(const std::string& id, std::int64_t rows = 8, std::int64_t cols = 12) {
  Scene s;
  s.statics.id = id;
  s.statics.body_faces = test::grid_faces_tensor(8, 16);
  s.body_rest = grid_cylinder(8, 16, 0.12f, 0.8f);
  s.statics.garments.push_back(grid_garment("inner", 0, grid_cylinder(rows, cols, 0.15f, 0.6f), rows, cols));
  s.statics.garments.push_back(grid_garment("outer", 1, grid_cylinder(rows, cols, 0.18f, 0.6f), rows, cols));
  return s;
}

}  // namespace layers::mgnet::testing
