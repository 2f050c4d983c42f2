// tests/support/synthetic_sequence.h -- test fixtures for layers::data: deterministic synthetic
// sequences (grid.h meshes on cylinders moving with a root, random skinning,
// wind spans), HDF5 tampering helpers to make
// bad files, and an exact comparison of two sequences.
#pragma once

#include <H5Cpp.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "grid.h"
#include "layers/data/sequence.h"
#include "temp_dir.h"

namespace layers::data::testing {

struct SyntheticSize {
  std::int64_t frames = 12;
  int body_rows = 10, body_cols = 20;       // 200 body vertices
  int garment_rows = 8, garment_cols = 16;  // 128 vertices per garment
  int joints = 5;
  int garments = 2;
};

// Vertices of the grid wrapped on a cylinder of the given radius and height.
inline std::vector<float> grid_cylinder(int rows, int cols, float radius, float height) {
  std::vector<float> out;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const float angle = 6.2831853f * float(c) / float(cols);
      out.insert(out.end(), {radius * std::cos(angle), height * float(r) / float(rows - 1), radius * std::sin(angle)});
    }
  }
  return out;
}

inline std::vector<float> unit_quaternions(std::int64_t n, std::mt19937_64& rng) {
  std::normal_distribution<float> normal(0.0f, 1.0f);
  std::vector<float> out;
  for (std::int64_t i = 0; i < n; ++i) {
    float q[4] = {normal(rng) + 2.0f, normal(rng), normal(rng), normal(rng)};
    const float norm = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
    for (float v : q) out.push_back(v / norm);
  }
  return out;
}

// Per-frame positions: rest + root(t) + a small deterministic wobble.
inline std::vector<float> animate(const std::vector<float>& rest, const std::vector<float>& root, std::int64_t frames,
                                  std::mt19937_64& rng) {
  std::uniform_real_distribution<float> noise(-0.005f, 0.005f);
  std::vector<float> out(static_cast<std::size_t>(frames) * rest.size());
  for (std::int64_t t = 0; t < frames; ++t) {
    float* frame = out.data() + t * rest.size();
    const float wobble = 0.01f * std::sin(0.3f * float(t));
    for (std::size_t i = 0; i < rest.size(); ++i) frame[i] = rest[i] + root[3 * t + i % 3] + wobble + noise(rng);
  }
  return out;
}

inline SequenceData make_sequence(const std::string& id, std::uint64_t seed, const SyntheticSize& size = {}) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  const std::int64_t T = size.frames;
  SequenceData seq;
  seq.id = id;
  seq.n_frames = T;
  seq.motion = "walk_" + std::to_string(seed % 7);
  seq.seed = seed;
  seq.tags = {seed % 2 ? "T+W" : "T", "synthetic"};
  seq.shape = {{"gender", unit(rng)}, {"height", 0.5 + unit(rng)}};

  std::vector<float> root;
  for (std::int64_t t = 0; t < T; ++t) {
    root.insert(root.end(), {0.02f * float(t) + 0.1f * unit(rng), 0.9f, 0.01f * float(t)});
  }
  BodyData& b = seq.body;
  b.faces = test::grid_faces<std::int32_t>(size.body_rows, size.body_cols);
  b.positions = animate(grid_cylinder(size.body_rows, size.body_cols, 0.15f, 1.6f), root, T, rng);
  b.root = root;
  b.root_rot = unit_quaternions(T, rng);
  for (int j = 0; j < size.joints; ++j) {
    b.joint_names.push_back("joint" + std::to_string(j));
    b.joint_parents.push_back(j == 0 ? -1 : (j - 1) / 2);
  }
  for (std::int64_t t = 0; t < T; ++t) {
    for (int j = 0; j < size.joints; ++j) {
      const float m[12] = {1, 0, 0, root[3 * t], 0, 1, 0, root[3 * t + 1] + 0.1f * j, 0, 0, 1, root[3 * t + 2]};
      b.joints.insert(b.joints.end(), m, m + 12);
    }
  }
  const int Vb = size.body_rows * size.body_cols;
  for (int v = 0; v < Vb; ++v) {
    float w[4], sum = 0.0f;
    for (int k = 0; k < 4; ++k) {
      b.skin_index.push_back(static_cast<std::int32_t>(rng() % size.joints));
      w[k] = unit(rng) + 0.01f;
      sum += w[k];
    }
    for (float x : w) b.skin_weight.push_back(x / sum);
  }
  // Wind: spans of 5 frames, each with one direction and strength.
  std::vector<float> span_rot;
  float strength = 0.0f;
  for (std::int64_t t = 0; t < T; ++t) {
    if (t % 5 == 0) {
      span_rot = unit_quaternions(1, rng);
      strength = 400.0f * unit(rng);
    }
    seq.wind.rotation.insert(seq.wind.rotation.end(), span_rot.begin(), span_rot.end());
    seq.wind.strength.push_back(strength);
  }
  const char* types[] = {"tshirt", "jacket"};
  for (int k = 0; k < size.garments; ++k) {
    GarmentData g;
    g.type = types[k % 2];
    g.name = g.type + (k >= 2 ? std::to_string(k) : "");
    g.layer = k % 2;
    g.attributes = {
        {"mass", 0.2 + 0.6 * unit(rng)}, {"tension", 15 + 85 * unit(rng)}, {"bending", 15 + 185 * unit(rng)}};
    g.faces = test::grid_faces<std::int32_t>(size.garment_rows, size.garment_cols);
    g.rest = grid_cylinder(size.garment_rows, size.garment_cols, 0.2f + 0.03f * k, 0.7f);
    for (int r = 0; r < size.garment_rows; ++r) {
      for (int c = 0; c < size.garment_cols; ++c) {
        g.uv.insert(g.uv.end(), {float(c) / float(size.garment_cols - 1), float(r) / float(size.garment_rows - 1)});
      }
    }
    g.uv_faces = g.faces;
    for (std::size_t f = 0; f < g.faces.size() / 3; ++f) g.panel.push_back(static_cast<std::int32_t>(f / 10 % 3));
    g.positions = animate(g.rest, root, T, rng);
    seq.garments.push_back(std::move(g));
  }
  return seq;
}

using layers::test::TempDir;

inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << text;
}

// Replaces (or creates) dataset `object` in an HDF5 file with the given
// type, shape and raw data (nullptr: leave uninitialised zeros).
inline void replace_dataset(const std::string& file, const std::string& object, const H5::PredType& type,
                            const std::vector<hsize_t>& dims, const void* data) {
  H5::H5File f(file, H5F_ACC_RDWR);
  if (H5Lexists(f.getId(), object.c_str(), H5P_DEFAULT) > 0) f.unlink(object);
  H5::DataSet ds = f.createDataSet(object, type, H5::DataSpace(static_cast<int>(dims.size()), dims.data()));
  if (data) ds.write(data, type);
}

inline void remove_object(const std::string& file, const std::string& object) {
  H5::H5File f(file, H5F_ACC_RDWR);
  f.unlink(object);
}

// Overwrites one element of an existing float32 or int32 dataset.
template <class T>
void poke(const std::string& file, const std::string& object, const std::vector<hsize_t>& index, T value) {
  H5::H5File f(file, H5F_ACC_RDWR);
  H5::DataSet ds = f.openDataSet(object);
  H5::DataSpace space = ds.getSpace();
  space.selectElements(H5S_SELECT_SET, 1, index.data());
  const hsize_t one = 1;
  H5::DataSpace mem(1, &one);
  ds.write(&value, std::is_same<T, float>::value ? H5::PredType::NATIVE_FLOAT : H5::PredType::NATIVE_INT32, mem, space);
}

inline void expect_same(const SequenceData& a, const SequenceData& b) {
  EXPECT_EQ(a.id, b.id);
  EXPECT_EQ(a.n_frames, b.n_frames);
  EXPECT_EQ(a.motion, b.motion);
  EXPECT_EQ(a.seed, b.seed);
  EXPECT_EQ(a.tags, b.tags);
  EXPECT_EQ(a.shape, b.shape);
  EXPECT_EQ(a.body.faces, b.body.faces);
  EXPECT_EQ(a.body.positions, b.body.positions);
  EXPECT_EQ(a.body.root, b.body.root);
  EXPECT_EQ(a.body.root_rot, b.body.root_rot);
  EXPECT_EQ(a.body.joints, b.body.joints);
  EXPECT_EQ(a.body.joint_names, b.body.joint_names);
  EXPECT_EQ(a.body.joint_parents, b.body.joint_parents);
  EXPECT_EQ(a.body.skin_index, b.body.skin_index);
  EXPECT_EQ(a.body.skin_weight, b.body.skin_weight);
  EXPECT_EQ(a.body.tpose_joints, b.body.tpose_joints);
  EXPECT_EQ(a.wind.rotation, b.wind.rotation);
  EXPECT_EQ(a.wind.strength, b.wind.strength);
  ASSERT_EQ(a.garments.size(), b.garments.size());
  for (std::size_t k = 0; k < a.garments.size(); ++k) {
    const GarmentData &x = a.garments[k], &y = b.garments[k];
    EXPECT_EQ(x.name, y.name);
    EXPECT_EQ(x.type, y.type);
    EXPECT_EQ(x.layer, y.layer);
    EXPECT_EQ(x.attributes, y.attributes);
    EXPECT_EQ(x.faces, y.faces);
    EXPECT_EQ(x.rest, y.rest);
    EXPECT_EQ(x.uv, y.uv);
    EXPECT_EQ(x.uv_faces, y.uv_faces);
    EXPECT_EQ(x.panel, y.panel);
    EXPECT_EQ(x.positions, y.positions);
  }
}

// Rows [first, first + count) of a row-major [T, ...] array.
inline std::vector<float> frames_of(const std::vector<float>& all, std::int64_t frames, std::int64_t first,
                                    std::int64_t count) {
  const std::size_t row = all.size() / static_cast<std::size_t>(frames);
  return std::vector<float>(all.begin() + first * row, all.begin() + (first + count) * row);
}

}  // namespace layers::data::testing
