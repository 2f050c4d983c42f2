// layers/body/pose_body.h -- one posed frame of a shaped body: the joint
// transforms of a pose (forward kinematics) and the skin they deform.
#pragma once

#include "layers/body/body_model.h"
#include "layers/body/skeleton.h"
#include "layers/geometry/mesh.h"

namespace layers::body {

struct BodyFrame {
  geometry::Points vertices;  // [Vb, 3]
  JointTransforms joints;
};
BodyFrame pose_body(const Body& body, const Pose& pose);

}  // namespace layers::body
