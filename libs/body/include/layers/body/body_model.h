// layers/body/body_model.h -- the MPFB2 (MakeHuman hm08) body.
//
// BodyModel loads the CC0 assets once (base mesh, shape targets, the
// 31-bone cmu_mb rig, skinning weights, T-pose) and builds shaped bodies:
// targets are blended the way MakeHuman's macro modifiers do, applied to
// all base vertices (skin, helpers and joint cubes), then the skin
// (vertices of the `body` group, faces whose vertices are all skin,
// quads split into triangles) is cut out, converted from decimetres to
// metres and lifted so that the soles touch y = 0. Joint positions are
// the means of the shaped joint cubes, so the skeleton follows the shape.
#pragma once

#include <array>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "layers/body/skeleton.h"
#include "layers/body/skinning.h"
#include "layers/core/config.h"
#include "layers/geometry/mesh.h"

namespace layers::body {

// MakeHuman macro parameters, each in 0..1 (0.5 = average).
struct ShapeParams {
  double gender = 0.5;  // 0 female .. 1 male
  double muscle = 0.5;
  double weight = 0.5;
  double height = 0.5;

  template <class V>
  void visit(V& v) {
    v("gender", gender, cfg::opt().range(0, 1).help("0 = female, 1 = male"));
    v("muscle", muscle, cfg::opt().range(0, 1).help("0.5 = average"));
    v("weight", weight, cfg::opt().range(0, 1).help("0.5 = average"));
    v("height", height, cfg::opt().range(0, 1).help("0.5 = average"));
  }
};

// The linear weight of every shipped target for `shape` (target file stem,
// weight), zero weights left out. MakeHuman's rules: female = 1 - gender,
// male = gender; for muscle and weight, v < 0.5 blends min (1 - 2v) with
// average, v >= 0.5 blends average with max (2v - 1); a universal target
// gets gender * muscle * weight; the height targets (min/max, on top)
// gender * (1 - 2h) below 0.5 and gender * (2h - 1) above; the caucasian
// targets gender / 3 (the share MakeHuman's default ethnic mix gives it).
std::vector<std::pair<std::string, double>> target_weights(const ShapeParams& shape);

struct Body {
  ShapeParams shape;                      // the MPFB2 body's; unused for a user's body
  std::string file;                       // a user's body (generate/own_body.h): its file; "" for ours
  geometry::TriMesh rest;                 // skin in the rest (MPFB2 default, A-like) pose, metres, soles at y = 0
  Skeleton skeleton;                      // 31 cmu_mb joints
  SkinWeights weights;                    // per skin vertex, top 4 influences
  Pose t_pose;                            // the MPFB2 T-pose (root at its rest position)
  std::array<std::vector<int>, 2> soles;  // skin vertices on the left / right sole

  int num_vertices() const { return rest.num_vertices(); }
  // Height of the rest mesh (top of the head to the soles).
  double stature() const;
};

// The soles: skin vertices within kSoleHeight of the lowest rest vertex
// whose dominant joint is a foot or toe (LeftFoot, LeftToeBase; Right...).
// A body without those joints has none.
inline constexpr double kSoleHeight = 0.015;
std::array<std::vector<int>, 2> sole_vertices(const Body& body);

// Lowest sole point (y) of the left and right foot for posed joints.
std::array<double, 2> sole_heights(const Body& body, const JointTransforms& transforms);

class BodyModel {
 public:
  // Loads the assets under `asset_root` ("" = default_asset_root()). The
  // result is cached per root for the whole process; loading is
  // thread-safe. Throws InputError naming the file on missing or malformed
  // assets.
  static std::shared_ptr<const BodyModel> load(const std::string& asset_root = "");

  // A shaped body. Thread-safe.
  Body build(const ShapeParams& shape) const;

  const std::string& asset_root() const;
  int num_skin_vertices() const;

  ~BodyModel();
  BodyModel(const BodyModel&) = delete;
  BodyModel& operator=(const BodyModel&) = delete;

 private:
  struct Impl;
  explicit BodyModel(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace layers::body
