// tests/regression/synthetic_fixture.h -- the dataset the model goldens run
// on, written by the test itself: 6 sequences of 20 frames (3 train, 1 val,
// 2 test), a body and two garment layers (tshirt under jacket) on grid
// cylinders facing outwards, moved in closed form (a yawing, bobbing, walking root;
// the garments trailing the body by one frame, swinging and rippling; a skeleton whose
// joints carry the body exactly), with wind spans, skinning weights, the
// T-pose joints and all seven attributes. Nothing is simulated, so it is
// the same on every machine and does not depend on the generator (which
// has its own regression, test_generator_regression).
#pragma once

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/stats.h"
#include "synthetic_sequence.h"

namespace layers::regression {

namespace detail {

// Points [N,3] (flat, on a cylinder about +y) widened radially by `ripple`
// times a wave around the cylinder at `phase`, swayed along x in proportion
// to their height, turned by `yaw` about +y and moved by `offset`.
inline void place(const std::vector<float>& rest, float yaw, const float* offset, float sway, float ripple, float phase,
                  float* out) {
  const float c = std::cos(yaw), s = std::sin(yaw);
  for (std::size_t i = 0; i + 2 < rest.size(); i += 3) {
    const float angle = std::atan2(rest[i + 2], rest[i]);
    const float widen = 1.0f + ripple * std::sin(3.0f * angle + phase);
    const float x = widen * rest[i], y = rest[i + 1], z = widen * rest[i + 2];
    out[i] = c * x + s * z + offset[0] + sway * y;
    out[i + 1] = y + offset[1];
    out[i + 2] = -s * x + c * z + offset[2];
  }
}

// Triangles turned to face outwards (grid.h winds a cylinder's inwards).
inline void face_outwards(std::vector<std::int32_t>& faces) {
  for (std::size_t f = 0; f + 2 < faces.size(); f += 3) std::swap(faces[f + 1], faces[f + 2]);
}

inline data::SequenceData fixture_sequence(const std::string& id, std::uint64_t seed) {
  data::testing::SyntheticSize size;
  size.frames = 20;
  data::SequenceData seq = data::testing::make_sequence(id, seed, size);
  const std::int64_t T = size.frames;
  const float phase = 0.7f * float(seed), speed = 0.015f + 0.005f * float(seed % 3);
  auto yaw = [&](std::int64_t t) { return 0.25f * std::sin(0.2f * float(t) + phase); };
  std::vector<float> root(3 * T);
  for (std::int64_t t = 0; t < T; ++t) {
    root[3 * t] = speed * float(t);
    root[3 * t + 1] = 0.9f + 0.02f * std::sin(0.5f * float(t) + phase);  // a walking bob
    root[3 * t + 2] = 0.5f * speed * float(t);
  }
  data::BodyData& b = seq.body;
  b.root = root;
  b.root_rot.clear();
  for (std::int64_t t = 0; t < T; ++t)
    b.root_rot.insert(b.root_rot.end(), {std::cos(0.5f * yaw(t)), 0.0f, std::sin(0.5f * yaw(t)), 0.0f});
  // Joint j rests at (0, 0.1 j, 0) with identity rotation; at t it is turned
  // by yaw(t) and carried by the root, so skinning reproduces the body.
  const int J = size.joints;
  b.tpose_joints.clear();
  b.joints.clear();
  for (int j = 0; j < J; ++j) b.tpose_joints.insert(b.tpose_joints.end(), {1, 0, 0, 0, 0, 1, 0, 0.1f * j, 0, 0, 1, 0});
  for (std::int64_t t = 0; t < T; ++t) {
    const float c = std::cos(yaw(t)), s = std::sin(yaw(t)), *r = &root[3 * t];
    for (int j = 0; j < J; ++j) {
      const float y = 0.1f * j;
      b.joints.insert(b.joints.end(), {c, 0, s, r[0], 0, 1, 0, y + r[1], -s, 0, c, r[2]});
    }
  }
  const std::vector<float> body_rest = data::testing::grid_cylinder(size.body_rows, size.body_cols, 0.15f, 1.6f);
  for (std::int64_t t = 0; t < T; ++t)
    place(body_rest, yaw(t), &root[3 * t], 0.0f, 0.0f, 0.0f, b.positions.data() + t * body_rest.size());
  face_outwards(b.faces);
  for (data::GarmentData& g : seq.garments) {
    g.attributes = {
        {"mass", 0.3},     {"tension", 40},       {"compression", 30}, {"shear", 20}, {"bending", 60 + 40 * g.layer},
        {"friction", 0.4}, {"self_friction", 0.3}};
    const std::size_t n = g.rest.size();
    for (std::int64_t t = 0; t < T; ++t) {
      const std::int64_t lag = t == 0 ? 0 : t - 1;
      const float sway = 0.03f * std::sin(0.4f * float(t) + phase) * float(1 + g.layer);
      place(g.rest, yaw(lag), &root[3 * t], sway, 0.04f, 0.6f * float(t) + phase, g.positions.data() + t * n);
    }
    face_outwards(g.faces);
    g.uv_faces = g.faces;
  }
  return seq;
}

}  // namespace detail

// Writes the fixture into <parent>/<name> (dataset.yaml, splits.yaml, one
// shard, stats.h5) and returns that folder; a folder already holding it (a
// kept LAYERS_REGRESSION_DIR) is reused as it is. `alter_test`, when given,
// changes each test sequence before it is written (and hashed): a valid
// dataset that differs from the fixture on the test split only.
inline std::string write_fixture(const std::string& parent,
                                 const std::function<void(data::SequenceData&)>& alter_test = {},
                                 const std::string& name = "fixture") {
  const std::string dir = parent + "/" + name;
  if (std::filesystem::exists(dir + "/stats.h5")) return dir;
  data::DatasetWriterOptions options;
  options.sequences_per_shard = 6;
  data::DatasetWriter writer(dir, options);
  std::vector<std::string> ids;
  for (int s = 0; s < 6; ++s) {
    ids.push_back("seq" + std::to_string(s));
    data::SequenceData seq = detail::fixture_sequence(ids.back(), static_cast<std::uint64_t>(s + 1));
    if (alter_test && s >= 4) alter_test(seq);
    writer.add(seq);
  }
  writer.set_split("train", {ids[0], ids[1], ids[2]});
  writer.set_split("val", {ids[3]});
  writer.set_split("test", {ids[4], ids[5]});
  writer.finish();
  data::write_dataset_stats(dir, data::compute_stats(data::Dataset::open(dir)));
  return dir;
}

}  // namespace layers::regression
