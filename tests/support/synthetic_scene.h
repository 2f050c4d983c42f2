// tests/support/synthetic_scene.h -- a deterministic synthetic
// layered scene as the zoo sees it (for the LayersNet tests in
// plugins/layersnet/test and bench/bench_layersnet.cpp): a cylindrical "body" point grid with an
// inner and an outer cylindrical garment around it (open seam, two sewing
// panels each, UVs in metres = arc length x height), moving with a root
// that walks along x, the garments rippling, wind blowing in the second
// half. Header-only.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include <ATen/ATen.h>

#include "grid_tensor.h"
#include "layers/data/stats.h"
#include "layers/zoo/model.h"
#include "layers/zoo/normalization.h"

namespace layers::layersnet::testing {

struct SceneSize {
  int garment_rows = 10, garment_cols = 16;  // vertices per garment = rows x cols
  int body_rows = 12, body_cols = 24;
  int garments = 2;  // garment k sits 2.5 cm further out than garment k-1
  int frames = 8;
};

struct SyntheticScene {
  zoo::SequenceStatic statics;
  std::vector<at::Tensor> garments;  // [T,V_k,3] each
  at::Tensor body;                   // [T,Vb,3]
  at::Tensor root;                   // [T,3]
  at::Tensor wind_strength;          // [T]
  at::Tensor wind_rotation;          // [T,4]

  std::int64_t frames() const { return root.size(0); }

  // The step from t to t+1 (1 <= t <= frames - 2).
  zoo::StepInput input(std::int64_t t) const {
    zoo::StepInput in;
    for (const at::Tensor& g : garments) in.garments.push_back({g[t - 1], g[t]});
    in.body = body[t];
    in.body_next = body[t + 1];
    in.root = root.narrow(0, t - 1, 3);
    in.root_rot = at::tensor({1.0f, 0.0f, 0.0f, 0.0f}).repeat({3, 1});
    in.wind_rotation = wind_rotation.narrow(0, t, 2);
    in.wind_strength = wind_strength.narrow(0, t, 2);
    return in;
  }
  // Garment positions at t+1 (the step's target).
  std::vector<at::Tensor> target(std::int64_t t) const {
    std::vector<at::Tensor> out;
    for (const at::Tensor& g : garments) out.push_back(g[t + 1]);
    return out;
  }
};

namespace detail {

// Rest positions of a rows x cols grid on a cylinder (open seam) and its
// UVs (arc length, height), y from y0 to y0 + height.
inline std::array<at::Tensor, 2> cylinder(int rows, int cols, float radius, float y0, float height) {
  const at::Tensor angle = at::arange(cols, at::kFloat) * (6.2831853f / static_cast<float>(cols));
  const at::Tensor y = y0 + at::arange(rows, at::kFloat) * (height / static_cast<float>(rows - 1));
  const at::Tensor a = angle.unsqueeze(0).expand({rows, cols}), h = y.unsqueeze(1).expand({rows, cols});
  const at::Tensor pos = at::stack({radius * at::cos(a), h, radius * at::sin(a)}, 2).reshape({-1, 3});
  const at::Tensor uv = at::stack({radius * a, h - y0}, 2).reshape({-1, 2});
  return {pos, uv};
}

inline data::Moments moments(const at::Tensor& x) {
  const at::Tensor flat = x.reshape({-1, 3}).to(at::kDouble);
  const at::Tensor mean = flat.mean(0), std = flat.std(0, /*unbiased=*/false).clamp_min(1e-6);
  data::Moments m;
  for (int i = 0; i < 3; ++i) {
    m.mean[i] = mean[i].item<double>();
    m.std[i] = std[i].item<double>();
  }
  m.count = flat.size(0);
  return m;
}

}  // namespace detail

inline SyntheticScene make_scene(const SceneSize& size, const std::string& id = "synthetic") {
  SyntheticScene s;
  s.statics.id = id;
  const at::Tensor t = at::arange(size.frames, at::kFloat);
  s.root = at::stack({0.02f * t + 0.01f * at::sin(0.3f * t), 0.9f + 0.005f * at::sin(0.7f * t), at::zeros_like(t)}, 1);
  // Wind: calm, then blowing at 300 along +x in the second half.
  s.wind_strength = at::where(t >= size.frames / 2, at::full_like(t, 300.0f), at::zeros_like(t));
  s.wind_rotation = at::tensor({0.7071068f, 0.0f, 0.7071068f, 0.0f}).repeat({size.frames, 1});

  // Body: a cylinder from 0.4 m below to 0.4 m above the root, breathing
  // (radius +-2%) as it moves with the root.
  const auto body_rest = detail::cylinder(size.body_rows, size.body_cols, 0.12f, -0.4f, 0.8f)[0];
  s.statics.body_faces = test::grid_faces_tensor(size.body_rows, size.body_cols);
  const at::Tensor breath = 0.02f * at::sin(0.4f * t).reshape({-1, 1, 1}) * at::tensor({1.0f, 0.0f, 1.0f});
  s.body = body_rest.unsqueeze(0) * (1 + breath) + s.root.unsqueeze(1);

  for (int k = 0; k < size.garments; ++k) {
    const float radius = 0.14f + 0.025f * static_cast<float>(k);
    auto [rest, uv] = detail::cylinder(size.garment_rows, size.garment_cols, radius, -0.3f, 0.5f);
    zoo::GarmentStatic g;
    g.name = "garment" + std::to_string(k);
    g.type = k == 0 ? "jumpsuit" : "jacket";
    g.layer = k == 0 ? 0 : 1;
    g.faces = test::grid_faces_tensor(size.garment_rows, size.garment_cols);
    g.rest = rest;
    g.uv = uv;
    g.uv_faces = g.faces.clone();
    // Panel 0: the first half of the columns, panel 1: the rest.
    const at::Tensor first_column = g.faces.select(1, 0) % size.garment_cols;
    g.panel = (first_column >= size.garment_cols / 2).to(at::kLong);
    g.attributes = at::tensor({0.3f + 0.2f * static_cast<float>(k), 50.0f, 50.0f, 40.0f, 100.0f, 60.0f, 60.0f});
    s.statics.garments.push_back(g);

    // Ripples: a travelling wave in y and a radial breathing, a few mm.
    const at::Tensor angle = at::atan2(rest.select(1, 2), rest.select(1, 0));
    const at::Tensor phase = 0.5f * t.unsqueeze(1) + 3.0f * angle.unsqueeze(0) + 5.0f * rest.select(1, 1).unsqueeze(0);
    const at::Tensor radial = rest * at::tensor({1.0f, 0.0f, 1.0f}) / radius;
    const at::Tensor wave = 0.01f * at::sin(phase).unsqueeze(2) * at::tensor({0.0f, 1.0f, 0.0f}) +
                            0.004f * at::cos(phase).unsqueeze(2) * radial.unsqueeze(0);
    s.garments.push_back(rest.unsqueeze(0) + s.root.unsqueeze(1) + wave);
  }
  return s;
}

// Normalisation statistics of the scene itself (as stats.h5 would hold
// them for a training split made of it).
inline zoo::Normalization scene_normalization(const SyntheticScene& s) {
  auto quantities = [&](const at::Tensor& frames, data::Moments& p, data::Moments& v, data::Moments& a) {
    const at::Tensor rel = frames - s.root.unsqueeze(1);
    const at::Tensor vel = rel.narrow(0, 1, rel.size(0) - 1) - rel.narrow(0, 0, rel.size(0) - 1);
    p = detail::moments(rel);
    v = detail::moments(vel);
    a = detail::moments(vel.narrow(0, 1, vel.size(0) - 1) - vel.narrow(0, 0, vel.size(0) - 1));
  };
  data::NormStats stats;
  std::vector<at::Tensor> all;
  for (const at::Tensor& g : s.garments) all.push_back(g);
  quantities(at::cat(all, 1), stats.garment_position, stats.garment_velocity, stats.garment_acceleration);
  quantities(s.body, stats.body_position, stats.body_velocity, stats.body_acceleration);
  return zoo::Normalization::from_stats(stats);
}

}  // namespace layers::layersnet::testing
