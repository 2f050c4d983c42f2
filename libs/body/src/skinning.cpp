// Linear blend skinning (see skinning.h).
#include "layers/body/skinning.h"

#include "layers/core/error.h"

namespace layers::body {
namespace {

using Affine = Eigen::Matrix<double, 3, 4>;

// Per joint the affine map rest -> posed: [R | p - R rest].
std::vector<Affine> skinning_matrices(const Skeleton& skeleton, const JointTransforms& t) {
  std::vector<Affine> m(skeleton.num_joints());
  for (int j = 0; j < skeleton.num_joints(); ++j) {
    Mat3 r = t.rotation[j].toRotationMatrix();
    m[j].leftCols<3>() = r;
    m[j].col(3) = t.position[j] - r * skeleton.rest_head[j];
  }
  return m;
}

Vec3 skin_one(const std::vector<Affine>& m, const SkinWeights& w, const geometry::Points& rest, int v) {
  Affine blended = Affine::Zero();
  for (int k = 0; k < 4; ++k) {
    float wk = w.weight(v, k);
    if (wk != 0.0f) blended += static_cast<double>(wk) * m[w.index(v, k)];
  }
  Vec3 x = rest.row(v).transpose().cast<double>();
  return blended.leftCols<3>() * x + blended.col(3);
}

void check_sizes(const geometry::Points& rest, const SkinWeights& w) {
  if (rest.rows() != w.index.rows() || rest.rows() != w.weight.rows())
    throw Error("skinning: " + std::to_string(rest.rows()) + " vertices but weights for " +
                std::to_string(w.index.rows()));
}

}  // namespace

void joint_matrices(const JointTransforms& transforms, float* out) {
  for (std::size_t j = 0; j < transforms.rotation.size(); ++j) {
    Mat3 r = transforms.rotation[j].toRotationMatrix();
    for (int row = 0; row < 3; ++row) {
      for (int col = 0; col < 3; ++col) out[12 * j + 4 * row + col] = static_cast<float>(r(row, col));
      out[12 * j + 4 * row + 3] = static_cast<float>(transforms.position[j][row]);
    }
  }
}

void skin(const geometry::Points& rest, const SkinWeights& weights, const Skeleton& skeleton,
          const JointTransforms& transforms, geometry::Points& out) {
  check_sizes(rest, weights);
  std::vector<Affine> m = skinning_matrices(skeleton, transforms);
  out.resize(rest.rows(), 3);
  for (int v = 0; v < rest.rows(); ++v) out.row(v) = skin_one(m, weights, rest, v).transpose().cast<float>();
}

std::vector<Vec3> skin_subset(const geometry::Points& rest, const SkinWeights& weights, const Skeleton& skeleton,
                              const JointTransforms& transforms, const std::vector<int>& vertices) {
  check_sizes(rest, weights);
  std::vector<Affine> m = skinning_matrices(skeleton, transforms);
  std::vector<Vec3> out;
  out.reserve(vertices.size());
  for (int v : vertices) out.push_back(skin_one(m, weights, rest, v));
  return out;
}

}  // namespace layers::body
