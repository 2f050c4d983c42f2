// The data DeePSD skins with: body/tpose_joints of a generated scene is the
// T-pose the garments' rest shapes were made in. One tiny scene is
// simulated (a few frames, coarse garments); every recorded body frame,
// mapped back to the T-pose by inverting its skinning with body/joints and
// body/tpose_joints, gives the same T-pose body, the garments' rest
// vertices sit on that body (within the fitting clearances), and skinning
// the rest vertices from the T-pose to a frame with their nearest body
// vertex's weights lands them near the simulated garment (within 5 cm on
// average after the drape).
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "layers/core/config.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"
#include "layers/geometry/penetration.h"
#include "test_paths.h"

namespace layers {
namespace {

using Affine = Eigen::Matrix<double, 3, 4>;

Affine joint(const std::vector<float>& joints, std::size_t frame, std::size_t j, std::size_t n_joints) {
  const float* m = joints.data() + (frame * n_joints + j) * 12;
  Affine out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) out(r, c) = m[4 * r + c];
  return out;
}

// G(t) G(T)^-1 as [A | b]: a T-pose point x moves to A x + b.
Affine tpose_to_frame(const Affine& frame, const Affine& tpose) {
  Affine out;
  out.leftCols<3>() = frame.leftCols<3>() * tpose.leftCols<3>().transpose();
  out.col(3) = frame.col(3) - out.leftCols<3>() * tpose.col(3);
  return out;
}

struct Scene {
  data::SequenceData seq;
  std::size_t joints = 0, body_vertices = 0;

  // The skinning map of body vertex v from the T-pose to `frame`.
  Affine body_map(std::size_t v, std::size_t frame) const {
    Affine blended = Affine::Zero();
    for (int k = 0; k < 4; ++k) {
      const auto j = static_cast<std::size_t>(seq.body.skin_index[4 * v + k]);
      const double w = seq.body.skin_weight[4 * v + k];
      blended +=
          w * tpose_to_frame(joint(seq.body.joints, frame, j, joints), joint(seq.body.tpose_joints, 0, j, joints));
    }
    return blended;
  }
  // Body frame `frame` mapped back to the T-pose (inverse skinning).
  geometry::Points tpose_body(std::size_t frame) const {
    geometry::Points out(static_cast<Eigen::Index>(body_vertices), 3);
    for (std::size_t v = 0; v < body_vertices; ++v) {
      const Affine m = body_map(v, frame);
      const float* y = seq.body.positions.data() + (frame * body_vertices + v) * 3;
      const Eigen::Vector3d x = m.leftCols<3>().inverse() * (Eigen::Vector3d(y[0], y[1], y[2]) - m.col(3));
      out.row(static_cast<Eigen::Index>(v)) = x.transpose().cast<float>();
    }
    return out;
  }
};

const Scene& scene() {
  static const Scene s = [] {
    auto config =
        cfg::read<generate::GeneratorConfig>(cfg::load_file(test::source_dir() + "/configs/data/tiny.yaml"), "tiny");
    config.frames = 4;
    config.drape_frames = 4;
    config.body.transition_frames = 4;
    config.garments.fit.edge_length = 0.08;
    config.sim.validation.max_l_penetration = 1;
    config.sim.validation.max_h_penetration = 1;
    config.sim.validation.max_stretch = 100;
    config.sim.validation.max_h_crossing_clear = 1;
    const generate::SceneResult result = generate::simulate_scene(config, generate::sample_scene(config, 0));
    EXPECT_TRUE(result.ok);
    Scene out;
    out.seq = result.sequence;
    out.joints = static_cast<std::size_t>(out.seq.body.n_joints());
    out.body_vertices = static_cast<std::size_t>(out.seq.body.n_vertices());
    return out;
  }();
  return s;
}

TEST(DeepsdTposeData, TposeJointsAreRigidTransformsOfEveryJoint) {
  const Scene& s = scene();
  ASSERT_EQ(s.seq.body.tpose_joints.size(), s.joints * 12);
  for (std::size_t j = 0; j < s.joints; ++j) {
    const Affine g = joint(s.seq.body.tpose_joints, 0, j, s.joints);
    EXPECT_TRUE(g.allFinite());
    EXPECT_LT((g.leftCols<3>() * g.leftCols<3>().transpose() - Eigen::Matrix3d::Identity()).norm(), 1e-5) << j;
    EXPECT_NEAR(g.leftCols<3>().determinant(), 1.0, 1e-5) << j;
  }
}

TEST(DeepsdTposeData, EveryFrameMapsBackToOneTposeBodyUnderTheRestShapes) {
  const Scene& s = scene();
  const geometry::Points first = s.tpose_body(0);
  for (std::size_t t = 1; t < static_cast<std::size_t>(s.seq.n_frames); ++t) {
    EXPECT_LT((s.tpose_body(t) - first).cwiseAbs().maxCoeff(), 1e-4) << "frame " << t;
  }
  // The garments were fitted around this body: their rest vertices lie
  // outside its skin (measured: 0.8% of a dress's vertices behind it, none
  // of a jacket's; moving the body by 2 cm puts up to 6% behind) and
  // within a few centimetres of it (median 3.7 cm dress, 4.3 cm jacket).
  geometry::TriMesh mesh;
  mesh.vertices = first;
  mesh.faces = Eigen::Map<const geometry::Faces>(s.seq.body.faces.data(), s.seq.body.n_faces(), 3);
  const geometry::Surface body = geometry::Surface::from_mesh(mesh, "T-pose body");
  for (const auto& g : s.seq.garments) {
    const geometry::Points rest = Eigen::Map<const geometry::Points>(g.rest.data(), g.n_vertices(), 3);
    EXPECT_LT(static_cast<double>(body.count_behind(rest)) / static_cast<double>(rest.rows()), 0.02)
        << g.name << " share of rest vertices behind the T-pose body";
    Eigen::VectorXf distance;
    body.index().nearest_all(rest, &distance);
    std::vector<float> d(distance.data(), distance.data() + distance.size());
    std::sort(d.begin(), d.end());
    EXPECT_LT(d[d.size() / 2], 0.06) << g.name << " median distance to the T-pose body";
    EXPECT_LT(d.back(), 0.25) << g.name << " largest distance to the T-pose body";
  }
}

TEST(DeepsdTposeData, RestShapesSkinnedToAFrameLandNearTheSimulatedGarments) {
  const Scene& s = scene();
  const geometry::PointIndex body(s.tpose_body(0));
  const std::size_t frame = static_cast<std::size_t>(s.seq.n_frames) - 1;
  for (const auto& g : s.seq.garments) {
    const auto nv = static_cast<std::size_t>(g.n_vertices());
    const geometry::Points rest = Eigen::Map<const geometry::Points>(g.rest.data(), g.n_vertices(), 3);
    const Eigen::VectorXi nearest = body.nearest_all(rest);
    double total = 0;
    for (std::size_t v = 0; v < nv; ++v) {
      const Affine m = s.body_map(static_cast<std::size_t>(nearest[static_cast<Eigen::Index>(v)]), frame);
      const Eigen::Vector3d x = rest.row(static_cast<Eigen::Index>(v)).transpose().cast<double>();
      const float* p = g.positions.data() + (frame * nv + v) * 3;
      total += (m.leftCols<3>() * x + m.col(3) - Eigen::Vector3d(p[0], p[1], p[2])).norm();
    }
    EXPECT_LT(total / nv, 0.05) << g.name << " mean distance of the skinned rest shape to the simulation";
  }
}

}  // namespace
}  // namespace layers
