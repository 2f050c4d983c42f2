// tests/support/imported_skinning.h -- linear blend skinning of a user's
// body as libs/import read it (the tests' reference: the generator skins
// with body::skin), vertex v of frame f.
#pragma once

#include <Eigen/Core>

#include "layers/import/body_import.h"

namespace layers::test {

inline Eigen::Vector3d skinned_vertex(const import::ImportedBody& b, int f, Eigen::Index v) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  const Eigen::Vector3d x = b.rest.vertices.row(v).cast<double>().transpose();
  const import::BodyFrame& frame = b.frames[static_cast<std::size_t>(f)];
  for (int k = 0; k < 4; ++k) {
    const int j = b.skin_index(v, k);
    sum += b.skin_weight(v, k) * (frame.rotation[j] * (x - b.joint_rest[j]) + frame.position[j]);
  }
  return sum;
}

}  // namespace layers::test
