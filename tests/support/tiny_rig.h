// tiny_rig.h -- a small skinned, animated body for the rig tests, made in
// memory: a 1.7 m column of hexagonal rings (faces outwards) on three
// joints ("mixamorig:Hips" -> "mixamorig:Spine" -> "mixamorig:Head", so
// importers strip the namespace), the middle ring weighted half to Hips
// and half to Spine, and `frames` frames in which the hips walk along x
// and turn about y, the spine bends about z and the head nods about x.
// `posed(f)` is linear blend skinning of frame f worked out here, the
// reference every reader of the rig is compared with.
#pragma once

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "layers/data/skinned_glb.h"

namespace layers::test {

struct TinyRig {
  data::SkinnedBody body;
  int frames = 0;

  explicit TinyRig(int n_frames) : frames(n_frames) {
    const double heights[5] = {0.0, 0.45, 0.9, 1.3, 1.7};
    const int ring = 6;
    for (double y : heights)
      for (int c = 0; c < ring; ++c) {
        const double a = 2 * M_PI * c / ring;
        body.rest.insert(body.rest.end(), {static_cast<float>(0.15 * std::sin(a)), static_cast<float>(y),
                                           static_cast<float>(0.15 * std::cos(a))});
      }
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < ring; ++c) {
        const int a = r * ring + c, b = r * ring + (c + 1) % ring, d = a + ring, e = b + ring;
        body.faces.insert(body.faces.end(), {a, b, e, a, e, d});
      }
    body.joint_names = {"mixamorig:Hips", "mixamorig:Spine", "mixamorig:Head"};
    body.joint_parents = {-1, 0, 1};
    body.rest_joints = {0.0f, 0.95f, 0.0f, 0.0f, 1.2f, 0.0f, 0.0f, 1.5f, 0.0f};
    for (int r = 0; r < 5; ++r)
      for (int c = 0; c < ring; ++c) {
        if (r <= 2) body.skin_index.insert(body.skin_index.end(), {0, 0, 0, 0});
        if (r == 3) body.skin_index.insert(body.skin_index.end(), {0, 1, 0, 0});
        if (r == 4) body.skin_index.insert(body.skin_index.end(), {2, 0, 0, 0});
        if (r == 3)
          body.skin_weight.insert(body.skin_weight.end(), {0.5f, 0.5f, 0.0f, 0.0f});
        else
          body.skin_weight.insert(body.skin_weight.end(), {1.0f, 0.0f, 0.0f, 0.0f});
      }
    for (int f = 0; f < frames; ++f) {
      const auto [rotation, position] = pose(f);
      for (int j = 0; j < 3; ++j) {
        const Eigen::Matrix3d r = rotation[j].toRotationMatrix();
        for (int row = 0; row < 3; ++row) {
          for (int col = 0; col < 3; ++col) body.joints.push_back(static_cast<float>(r(row, col)));
          body.joints.push_back(static_cast<float>(position[j][row]));
        }
      }
    }
  }

  Eigen::Vector3d rest_joint(int j) const {
    return {body.rest_joints[j * 3], body.rest_joints[j * 3 + 1], body.rest_joints[j * 3 + 2]};
  }

  // World rotations relative to the bind pose and world positions of frame f.
  std::pair<std::vector<Eigen::Quaterniond>, std::vector<Eigen::Vector3d>> pose(int f) const {
    using Q = Eigen::Quaterniond;
    using A = Eigen::AngleAxisd;
    const Q hips(A(0.15 * f, Eigen::Vector3d::UnitY()));
    const Q spine = hips * Q(A(0.2 * f, Eigen::Vector3d::UnitZ()));
    const Q head = spine * Q(A(-0.1 * f, Eigen::Vector3d::UnitX()));
    const Eigen::Vector3d p0 = rest_joint(0) + Eigen::Vector3d(0.05 * f, 0.01 * f, 0.0);
    const Eigen::Vector3d p1 = p0 + hips * (rest_joint(1) - rest_joint(0));
    const Eigen::Vector3d p2 = p1 + spine * (rest_joint(2) - rest_joint(1));
    return {{hips, spine, head}, {p0, p1, p2}};
  }

  // The skinned vertices of frame f, [V,3] row-major.
  std::vector<double> posed(int f) const {
    const auto [rotation, position] = pose(f);
    std::vector<double> out;
    for (std::size_t v = 0; v < body.rest.size() / 3; ++v) {
      const Eigen::Vector3d x(body.rest[v * 3], body.rest[v * 3 + 1], body.rest[v * 3 + 2]);
      Eigen::Vector3d sum = Eigen::Vector3d::Zero();
      for (int k = 0; k < 4; ++k) {
        const int j = body.skin_index[v * 4 + k];
        sum += body.skin_weight[v * 4 + k] * (rotation[j] * (x - rest_joint(j)) + position[j]);
      }
      out.insert(out.end(), {sum.x(), sum.y(), sum.z()});
    }
    return out;
  }
};

}  // namespace layers::test
