// layers/body/skinning.h -- linear blend skinning with four influences
// per vertex (the `body/skin_index`, `body/skin_weight` arrays of
// LAYERS-H5), and the 3x4 joint matrices of `body/joints`.
#pragma once

#include <Eigen/Core>

#include "layers/body/skeleton.h"
#include "layers/geometry/mesh.h"

namespace layers::body {

struct SkinWeights {
  // Per vertex the four most influential joints (unused slots: joint 0
  // with weight 0) and their weights, renormalised to sum to 1.
  Eigen::Matrix<int, Eigen::Dynamic, 4, Eigen::RowMajor> index;
  Eigen::Matrix<float, Eigen::Dynamic, 4, Eigen::RowMajor> weight;
  int num_vertices() const { return static_cast<int>(index.rows()); }
};

// World transform of each joint as rows of a 3x4 matrix [R | p]: R the
// world rotation relative to rest, p the joint's world position (the
// layout of `body/joints`, 12 floats per joint). `out` must hold 12*J floats.
void joint_matrices(const JointTransforms& transforms, float* out);

// Skins `rest` (rest-pose vertices) into `out` (resized to match):
// x' = sum_k w_k (R_k (x - rest_k) + p_k).
void skin(const geometry::Points& rest, const SkinWeights& weights, const Skeleton& skeleton,
          const JointTransforms& transforms, geometry::Points& out);

// Skins only the listed vertices (rows of `rest`), e.g. foot soles.
std::vector<Vec3> skin_subset(const geometry::Points& rest, const SkinWeights& weights, const Skeleton& skeleton,
                              const JointTransforms& transforms, const std::vector<int>& vertices);

}  // namespace layers::body
