// plugins/deepsd/test/deepsd_fixture.h -- a synthetic skinned scene for the
// DeePSD tests: a 4-joint skeleton (root turned and moved, as the
// generator places the T-pose), a cylinder body skinned to it, two
// cylinder garments (inner, outer) around the body, and frames posed by
// rotating the joints; hand-computed linear blend skinning in double
// precision to compare against.
#pragma once

#include <ATen/ATen.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "grid.h"
#include "layers/zoo/model.h"
#include "params.h"

namespace layers::deepsd::testing {

constexpr int kJoints = 4;

struct Joint {
  Eigen::Matrix3d r;
  Eigen::Vector3d p;
};
using Skeleton = std::vector<Joint>;

// Model parameters for this skeleton at width w: graph layers {w, 2w},
// every head {2w}, a basis of w.
inline DeepsdParams scene_params(int w) {
  DeepsdParams p;
  p.joints = kJoints;
  p.graph_widths = {w, 2 * w};
  p.weight_head = {2 * w};
  p.deformation_head = {2 * w};
  p.pose_head = {2 * w};
  p.basis = w;
  return p;
}

inline at::Tensor to_tensor(const Skeleton& s) {
  std::vector<float> out;
  for (const Joint& j : s)
    for (int r = 0; r < 3; ++r)
      out.insert(out.end(), {float(j.r(r, 0)), float(j.r(r, 1)), float(j.r(r, 2)), float(j.p[r])});
  return at::tensor(out).view({static_cast<std::int64_t>(s.size()), 3, 4});
}

// Rounds a skeleton through float32 so that hand computations use the
// values the model sees.
inline Skeleton as_float(const Skeleton& s) {
  Skeleton out = s;
  for (Joint& j : out) {
    j.r = j.r.cast<float>().cast<double>();
    j.p = j.p.cast<float>().cast<double>();
  }
  return out;
}

inline Eigen::Matrix3d rot(const Eigen::Vector3d& axis, double angle) {
  return Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
}

// The T-pose: joint j at height 0.9 + 0.2 j (joint 3 beside joint 1), each
// turned a little, the whole skeleton turned by 0.7 rad about y and moved.
inline Skeleton tpose() {
  const Eigen::Matrix3d heading = rot({0, 1, 0}, 0.7);
  const Eigen::Vector3d shift(0.3, 0.0, -0.2);
  const Eigen::Vector3d at[kJoints] = {{0, 0.9, 0}, {0, 1.1, 0}, {0, 1.3, 0}, {0.15, 1.1, 0}};
  Skeleton s(kJoints);
  for (int j = 0; j < kJoints; ++j) {
    s[j].r = heading * rot({1, 0.2 * j, 0.1}, 0.1 * j);
    s[j].p = heading * at[j] + shift;
  }
  return as_float(s);
}

// A frame: the T-pose with joint j turned by a phase-dependent angle
// about its own axis, and the root moved.
inline Skeleton posed(double phase) {
  const Skeleton t = tpose();
  Skeleton s = t;
  const Eigen::Vector3d axes[kJoints] = {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}, {1, 1, 0}};
  for (int j = 0; j < kJoints; ++j) {
    const Eigen::Matrix3d turn = rot(axes[j], (0.3 + 0.15 * j) * std::sin(phase + j));
    s[j].r = turn * t[j].r;
    s[j].p = t[j].p + Eigen::Vector3d(0.05 * std::sin(phase), 0.02 * j * std::cos(phase), 0.03 * phase);
  }
  return as_float(s);
}

// G_j(f) G_j(T)^-1 x.
inline Eigen::Vector3d move(const Joint& frame, const Joint& t, const Eigen::Vector3d& x) {
  return frame.r * t.r.transpose() * (x - t.p) + frame.p;
}

// Hand-computed LBS from the T-pose with dense weights w [J] per vertex.
inline Eigen::Vector3d lbs(const Skeleton& frame, const Skeleton& t, const std::vector<double>& w,
                           const Eigen::Vector3d& x) {
  Eigen::Vector3d out = Eigen::Vector3d::Zero();
  for (int j = 0; j < kJoints; ++j) out += w[j] * move(frame[j], t[j], x);
  return out;
}

// Vertices of a rows x cols grid wrapped on a vertical cylinder (in the
// T-pose's frame: turned and moved like the skeleton) and its faces
// (grid.h, closed: the last column joins the first).
struct Grid {
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::int64_t> faces;
};
inline Grid cylinder(int rows, int cols, double radius, double bottom, double height) {
  const Eigen::Matrix3d heading = rot({0, 1, 0}, 0.7);
  const Eigen::Vector3d shift(0.3, 0.0, -0.2);
  Grid g;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const double a = 2 * M_PI * c / cols;
      const Eigen::Vector3d x(radius * std::cos(a), bottom + height * r / (rows - 1), radius * std::sin(a));
      g.vertices.push_back((heading * x + shift).cast<float>().cast<double>());
    }
  }
  g.faces = test::grid_faces(rows, cols, /*closed=*/true);
  return g;
}

inline at::Tensor points_tensor(const std::vector<Eigen::Vector3d>& points) {
  std::vector<float> out;
  for (const auto& p : points) out.insert(out.end(), {float(p.x()), float(p.y()), float(p.z())});
  return at::tensor(out).view({static_cast<std::int64_t>(points.size()), 3});
}

// Smooth skinning weights by height: joint 0 below, 1 and 2 above, a
// little of 3 on the +x side; four influences.
inline std::vector<double> height_weights(const Eigen::Vector3d& x) {
  const double h = std::clamp((x.y() - 0.8) / 0.6, 0.0, 1.0);
  std::vector<double> w{1 - h, h * (1 - h) * 2 + 0.05, h * h, 0.05 + 0.1 * std::max(0.0, x.x() - 0.3)};
  double sum = 0;
  for (double v : w) sum += v;
  for (double& v : w) v /= sum;
  return w;
}

struct Scene {
  Skeleton t = tpose();
  Grid body = cylinder(10, 16, 0.15, 0.8, 0.7);
  // Heights and angles chosen so that no garment vertex is equally far
  // from two body vertices (the nearest one is unique).
  std::vector<Grid> garments{cylinder(6, 12, 0.19, 0.86, 0.5), cylinder(6, 14, 0.23, 0.87, 0.55)};
  std::vector<std::vector<double>> body_weights;  // [Vb][J]

  Scene() {
    for (const auto& x : body.vertices) body_weights.push_back(height_weights(x));
  }

  zoo::SequenceStatic statics(const std::string& id = "synthetic") const {
    zoo::SequenceStatic s;
    s.id = id;
    s.body_faces = at::tensor(body.faces).view({-1, 3});
    s.joint_parents = at::tensor(std::vector<std::int64_t>{-1, 0, 1, 0});
    std::vector<std::int64_t> index;
    std::vector<float> weight;
    for (const auto& w : body_weights) {
      for (int j = 0; j < kJoints; ++j) {
        index.push_back(j);
        weight.push_back(float(w[j]));
      }
    }
    s.skin_index = at::tensor(index).view({-1, 4});
    s.skin_weight = at::tensor(weight).view({-1, 4});
    s.tpose_joints = to_tensor(t);
    const char* types[] = {"jumpsuit", "jacket"};
    for (std::size_t k = 0; k < garments.size(); ++k) {
      zoo::GarmentStatic g;
      g.name = g.type = types[k];
      g.layer = static_cast<std::int64_t>(k);
      g.faces = at::tensor(garments[k].faces).view({-1, 3});
      g.rest = points_tensor(garments[k].vertices);
      g.uv = g.rest.slice(1, 0, 2).clone();
      g.uv_faces = g.faces.clone();
      g.panel = at::zeros({g.faces.size(0)}, at::kLong);
      g.attributes = at::tensor({0.3f + 0.3f * k, 40.f, 60.f, 30.f, 120.f, 50.f, 70.f});
      s.garments.push_back(g);
    }
    return s;
  }

  // Body vertices skinned to `frame`.
  at::Tensor body_at(const Skeleton& frame) const {
    std::vector<Eigen::Vector3d> out;
    for (std::size_t v = 0; v < body.vertices.size(); ++v)
      out.push_back(lbs(frame, t, body_weights[v], body.vertices[v]));
    return points_tensor(out);
  }

  // The step input predicting `frame` (garment states: the rest shapes).
  zoo::StepInput input(const Skeleton& frame, double wind_strength = 120.0) const {
    zoo::StepInput in;
    for (const Grid& g : garments) {
      const at::Tensor rest = points_tensor(g.vertices);
      in.garments.push_back({rest, rest});
    }
    in.body = body_at(t);
    in.body_next = body_at(frame);
    in.root = at::zeros({3, 3});
    in.root_rot = at::tensor({1.f, 0.f, 0.f, 0.f}).repeat({3, 1});
    in.wind_rotation = at::tensor({0.9238795f, 0.f, 0.3826834f, 0.f}).repeat({2, 1});
    in.wind_strength = at::full({2}, float(wind_strength));
    in.joints = to_tensor(t);
    in.joints_next = to_tensor(frame);
    return in;
  }
};

}  // namespace layers::deepsd::testing
