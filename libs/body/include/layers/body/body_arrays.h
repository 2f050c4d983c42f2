// layers/body/body_arrays.h -- the per-body arrays of LAYERS-H5 and the
// rest pose a skinning model needs, taken from a shaped body.
#pragma once

#include <string>
#include <vector>

#include "layers/body/body_model.h"

namespace layers::body {

// Per-body arrays of LAYERS-H5 (`body/faces`, `body/joint_names`,
// `body/joint_parents`, `body/skin_index`, `body/skin_weight`), plus the
// rest pose a skinning model needs to use `body/joints`: with joint j's
// frame [R | p], a rest point x moves to R (x - rest_joints[j]) + p.
struct BodyArrays {
  std::vector<int> faces;  // [Fb, 3]
  std::vector<std::string> joint_names;
  std::vector<int> joint_parents;    // -1 for the root
  std::vector<int> skin_index;       // [Vb, 4]
  std::vector<float> skin_weight;    // [Vb, 4]
  std::vector<float> rest_joints;    // [J, 3]
  std::vector<float> rest_vertices;  // [Vb, 3]
};
BodyArrays body_arrays(const Body& body);

}  // namespace layers::body
