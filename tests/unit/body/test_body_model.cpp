// Body model: skin cut, units, shapes (height monotonic), mesh closed and
// consistently oriented for every shape, skeleton and T-pose.
#include <gtest/gtest.h>

#include <cstdlib>
#include <map>

#include "body_fixture.h"
#include "layers/core/error.h"
#include "layers/geometry/normals.h"
#include "test_paths.h"

namespace layers::body {
namespace {

using test::body;
using test::shape;

TEST(BodyModel, SkinIsCutTriangulatedAndInMetres) {
  const Body& b = body();
  EXPECT_EQ(b.num_vertices(), 13380);
  EXPECT_EQ(b.rest.num_faces(), 2 * 13378);  // every skin quad split in two
  EXPECT_EQ(b.rest.faces.maxCoeff(), 13379);
  EXPECT_NEAR(b.rest.vertices.col(1).minCoeff(), 0.0f, 1e-6f);  // soles on the ground
  EXPECT_GT(b.stature(), 1.55);
  EXPECT_LT(b.stature(), 1.80);  // the average MakeHuman body is about 1.67 m
  // y is up, the body faces +z: the nose is in front of the heels.
  EXPECT_GT(b.rest.vertices.col(2).maxCoeff(), 0.1f);
}

TEST(BodyModel, TargetWeightsFollowMakeHuman) {
  auto weights = [](const ShapeParams& s) {
    std::map<std::string, double> m;
    for (const auto& [name, w] : target_weights(s)) m[name] = w;
    return m;
  };
  auto avg = weights({});
  EXPECT_DOUBLE_EQ(avg["universal-female-young-averagemuscle-averageweight"], 0.5);
  EXPECT_DOUBLE_EQ(avg["universal-male-young-averagemuscle-averageweight"], 0.5);
  EXPECT_EQ(avg.count("female-young-averagemuscle-averageweight-maxheight"), 0u);
  auto s = weights(shape(1.0, 0.25, 0.75, 0.9));
  EXPECT_EQ(s.count("universal-female-young-averagemuscle-averageweight"), 0u);
  EXPECT_NEAR(s["universal-male-young-minmuscle-averageweight"], 0.5 * 0.5, 1e-12);
  EXPECT_NEAR(s["universal-male-young-minmuscle-maxweight"], 0.5 * 0.5, 1e-12);
  EXPECT_NEAR(s["universal-male-young-averagemuscle-maxweight"], 0.5 * 0.5, 1e-12);
  EXPECT_NEAR(s["male-young-averagemuscle-averageweight-maxheight"], 0.8, 1e-12);
  double universal = 0.0;
  for (const auto& [name, w] : s)
    if (name.rfind("universal-", 0) == 0) universal += w;
  EXPECT_NEAR(universal, 1.0, 1e-12);
}

TEST(BodyModel, HeightParameterIsMonotonic) {
  for (double gender : {0.0, 1.0}) {
    double previous = 0.0;
    for (double h = 0.0; h <= 1.0 + 1e-9; h += 0.125) {
      const double stature = test::model()->build(shape(gender, 0.5, 0.5, h)).stature();
      EXPECT_GT(stature, previous + 0.01) << "gender " << gender << " height " << h;
      previous = stature;
    }
  }
}

// Each directed edge appears once and its reverse once: a closed,
// consistently oriented (outward) surface. Holds for the hm08 skin: its
// eye sockets and mouth are closed by skin faces (no boundary loops).
void expect_closed_and_oriented(const Body& b) {
  std::map<std::pair<int, int>, int> directed;
  for (int f = 0; f < b.rest.num_faces(); ++f)
    for (int k = 0; k < 3; ++k) ++directed[{b.rest.faces(f, k), b.rest.faces(f, (k + 1) % 3)}];
  int duplicated = 0, boundary = 0;
  for (const auto& [e, count] : directed) {
    duplicated += count != 1;
    boundary += directed.count({e.second, e.first}) == 0;
  }
  EXPECT_EQ(duplicated, 0);
  EXPECT_EQ(boundary, 0);
  // Outward: the signed volume is positive and a human's (15-300 litres
  // over the whole shape range).
  double volume = 0.0;
  for (int f = 0; f < b.rest.num_faces(); ++f) {
    Eigen::Vector3d p[3];
    for (int k = 0; k < 3; ++k) p[k] = b.rest.vertices.row(b.rest.faces(f, k)).transpose().cast<double>();
    volume += p[0].dot(p[1].cross(p[2])) / 6.0;
  }
  EXPECT_GT(volume, 0.015);
  EXPECT_LT(volume, 0.3);
}

TEST(BodyModel, EveryShapeIsClosedAndConsistentlyOriented) {
  for (double g : {0.0, 1.0})
    for (double m : {0.0, 1.0})
      for (double w : {0.0, 1.0})
        for (double h : {0.0, 1.0}) expect_closed_and_oriented(test::model()->build(shape(g, m, w, h)));
  expect_closed_and_oriented(body());
}

TEST(BodyModel, SkeletonFollowsTheShape) {
  const Body& b = body();
  const Skeleton& sk = b.skeleton;
  ASSERT_EQ(sk.num_joints(), 31);
  EXPECT_EQ(sk.names[0], "Hips");
  EXPECT_EQ(sk.parents[0], -1);
  for (int j = 1; j < sk.num_joints(); ++j) EXPECT_LT(sk.parents[j], j) << sk.names[j];
  for (const char* name : {"LeftUpLeg", "LeftLeg", "LeftFoot", "Spine1", "Neck", "Head", "LeftArm", "LeftForeArm",
                           "LeftHand", "RightArm", "RightToeBase", "LThumb", "RHipJoint"})
    EXPECT_GE(sk.index(name), 0) << name;
  // Joints sit inside the body's extent and follow the height parameter.
  const Body& tall = body(shape(0.5, 0.5, 0.5, 1.0));
  const int head = sk.require("Head");
  EXPECT_GT(tall.skeleton.rest_head[head].y(), sk.rest_head[head].y() + 0.2);
  EXPECT_NEAR(sk.rest_head[sk.require("LeftArm")].x(), -sk.rest_head[sk.require("RightArm")].x(), 1e-4);
  // Skin weights: four per vertex, summing to one.
  EXPECT_EQ(b.weights.num_vertices(), b.num_vertices());
  EXPECT_NEAR((b.weights.weight.rowwise().sum().array() - 1.0f).abs().maxCoeff(), 0.0f, 1e-5f);
  EXPECT_GE(b.weights.weight.minCoeff(), 0.0f);
}

TEST(BodyModel, TPoseHasHorizontalArmsAndGroundedFeet) {
  const Body& b = body();
  const Skeleton& sk = b.skeleton;
  const JointTransforms t = forward_kinematics(sk, b.t_pose);
  for (const char* side : {"Left", "Right"}) {
    const Vec3 shoulder = t.position[sk.require(std::string(side) + "Arm")];
    const Vec3 hand = t.position[sk.require(std::string(side) + "Hand")];
    const Vec3 arm = hand - shoulder;
    EXPECT_LT(std::abs(arm.y()) / arm.norm(), 0.15) << side;  // within ~9 degrees of horizontal
  }
  const auto soles = sole_heights(b, t);
  EXPECT_NEAR(std::min(soles[0], soles[1]), 0.0, 1e-6);
}

TEST(BodyModel, AssetRootComesFromTheEnvironmentOrTheBuild) {
  const char* saved = std::getenv("LAYERS_ASSETS");
  const std::string before = saved ? saved : "";
  ::setenv("LAYERS_ASSETS", "/somewhere/assets", 1);
  EXPECT_EQ(default_asset_root(), "/somewhere/assets");
  EXPECT_EQ(body_asset_dir(""), "/somewhere/assets/body/mpfb2");
  EXPECT_EQ(resolve_asset_root("/explicit"), "/explicit");
  // Motion names are recorded relative to the root's motions/ folder;
  // a file outside it keeps its absolute path.
  EXPECT_EQ(asset_relative_name("/somewhere/assets/motions/cmu/a.bvh", ""), "cmu/a.bvh");
  EXPECT_EQ(asset_relative_name("/somewhere/assets/motions/../other/a.bvh", ""), "/somewhere/assets/other/a.bvh");
  EXPECT_EQ(asset_relative_name("/elsewhere/b.bvh", "/explicit"), "/elsewhere/b.bvh");
  ::unsetenv("LAYERS_ASSETS");
  // Not installed (the test binary has no ../share/layers/assets): the
  // repository's own assets/ folder, never anything outside the clone.
  EXPECT_EQ(default_asset_root(), layers::test::source_dir() + "/assets");
  if (saved) ::setenv("LAYERS_ASSETS", before.c_str(), 1);
}

TEST(BodyModel, RejectsOutOfRangeShapesAndMissingAssets) {
  EXPECT_THROW(test::model()->build(shape(1.5, 0.5, 0.5, 0.5)), InputError);
  try {
    BodyModel::load("/nonexistent/assets");
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/assets/body/mpfb2/base.obj"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace layers::body
