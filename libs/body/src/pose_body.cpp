// Posing a shaped body (see pose_body.h).
#include "layers/body/pose_body.h"

#include "layers/body/skinning.h"

namespace layers::body {

BodyFrame pose_body(const Body& body, const Pose& pose) {
  BodyFrame f;
  f.joints = forward_kinematics(body.skeleton, pose);
  skin(body.rest.vertices, body.weights, body.skeleton, f.joints, f.vertices);
  return f;
}

}  // namespace layers::body
