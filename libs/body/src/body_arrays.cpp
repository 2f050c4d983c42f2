// The per-body arrays of LAYERS-H5 (see body_arrays.h).
#include "layers/body/body_arrays.h"

namespace layers::body {

BodyArrays body_arrays(const Body& body) {
  BodyArrays a;
  a.faces.assign(body.rest.faces.data(), body.rest.faces.data() + body.rest.faces.size());
  a.joint_names = body.skeleton.names;
  a.joint_parents = body.skeleton.parents;
  a.skin_index.assign(body.weights.index.data(), body.weights.index.data() + body.weights.index.size());
  a.skin_weight.assign(body.weights.weight.data(), body.weights.weight.data() + body.weights.weight.size());
  for (const Vec3& p : body.skeleton.rest_head)
    for (int k = 0; k < 3; ++k) a.rest_joints.push_back(static_cast<float>(p[k]));
  a.rest_vertices.assign(body.rest.vertices.data(), body.rest.vertices.data() + body.rest.vertices.size());
  return a;
}

}  // namespace layers::body
