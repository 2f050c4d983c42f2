// Linear blend skinning and joint transforms.
#include <gtest/gtest.h>

#include "body_fixture.h"
#include "layers/body/body_arrays.h"
#include "layers/body/pose_body.h"
#include "layers/body/skinning.h"

namespace layers::body {
namespace {

TEST(Skinning, IdentityPoseReproducesTheRestMesh) {
  const Body& b = test::body();
  geometry::Points out;
  skin(b.rest.vertices, b.weights, b.skeleton, forward_kinematics(b.skeleton, rest_pose(b.skeleton)), out);
  ASSERT_EQ(out.rows(), b.rest.vertices.rows());
  EXPECT_LE((out - b.rest.vertices).cwiseAbs().maxCoeff(), 1e-6f);
}

TEST(Skinning, RigidMotionOfTheRootMovesEverythingRigidly) {
  const Body& b = test::body();
  Pose p = rest_pose(b.skeleton);
  const Quat r = axis_angle(Vec3(0.3, 1.0, -0.2), 0.8);
  p.local[0] = r;
  p.root += Vec3(0.5, 0.1, -2.0);
  geometry::Points out;
  skin(b.rest.vertices, b.weights, b.skeleton, forward_kinematics(b.skeleton, p), out);
  double err = 0.0;
  for (int v = 0; v < b.num_vertices(); ++v) {
    const Vec3 x = b.rest.vertices.row(v).transpose().cast<double>();
    const Vec3 expected = r * (x - b.skeleton.rest_head[0]) + p.root;
    err = std::max(err, (expected - out.row(v).transpose().cast<double>()).norm());
  }
  EXPECT_LT(err, 1e-5);
}

TEST(Skinning, JointMatricesMatchTheLayout) {
  const Body& b = test::body();
  Pose p = rest_pose(b.skeleton);
  const int elbow = b.skeleton.require("LeftForeArm");
  p.local[elbow] = rot_z(0.5);
  const JointTransforms t = forward_kinematics(b.skeleton, p);
  std::vector<float> m(12 * b.skeleton.num_joints());
  joint_matrices(t, m.data());
  const Mat3 r = t.rotation[elbow].toRotationMatrix();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) EXPECT_NEAR(m[12 * elbow + 4 * row + col], r(row, col), 1e-6);
    EXPECT_NEAR(m[12 * elbow + 4 * row + 3], t.position[elbow][row], 1e-6);
  }
  // A child of the rotated joint moves, its parent does not.
  EXPECT_GT((t.position[b.skeleton.require("LeftHand")] - b.skeleton.rest_head[b.skeleton.require("LeftHand")]).norm(),
            0.05);
  EXPECT_LT((t.position[elbow] - b.skeleton.rest_head[elbow]).norm(), 1e-9);
}

TEST(Skinning, BodyArraysHaveTheH5Shapes) {
  const Body& b = test::body();
  const BodyArrays a = body_arrays(b);
  EXPECT_EQ(a.faces.size(), static_cast<std::size_t>(3 * b.rest.num_faces()));
  EXPECT_EQ(a.joint_names.size(), 31u);
  EXPECT_EQ(a.joint_parents.size(), 31u);
  EXPECT_EQ(a.skin_index.size(), static_cast<std::size_t>(4 * b.num_vertices()));
  EXPECT_EQ(a.skin_weight.size(), static_cast<std::size_t>(4 * b.num_vertices()));
  EXPECT_EQ(a.rest_joints.size(), 31u * 3);
  EXPECT_EQ(a.rest_vertices.size(), static_cast<std::size_t>(3 * b.num_vertices()));
  // Skinning from the stored arrays alone reproduces a posed frame.
  Pose p = rest_pose(b.skeleton);
  p.local[b.skeleton.require("LeftUpLeg")] = rot_x(-0.6);
  p.local[b.skeleton.require("RightForeArm")] = rot_y(0.4);
  const BodyFrame frame = pose_body(b, p);
  std::vector<float> m(12 * 31);
  joint_matrices(frame.joints, m.data());
  double err = 0.0;
  for (int v = 0; v < b.num_vertices(); v += 7) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int k = 0; k < 4; ++k) {
      const int j = a.skin_index[4 * v + k];
      const double w = a.skin_weight[4 * v + k];
      for (int row = 0; row < 3; ++row) {
        double y = m[12 * j + 4 * row + 3];
        for (int col = 0; col < 3; ++col)
          y += m[12 * j + 4 * row + col] * (a.rest_vertices[3 * v + col] - a.rest_joints[3 * j + col]);
        x[row] += w * y;
      }
    }
    err = std::max(err, (x - frame.vertices.row(v).transpose().cast<double>()).norm());
  }
  EXPECT_LT(err, 1e-5);
}

}  // namespace
}  // namespace layers::body
