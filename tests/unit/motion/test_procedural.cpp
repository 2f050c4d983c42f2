// Procedural motions: every kind builds, is deterministic for a seed,
// varies with the seed, is smooth (bounded first and second differences of
// joint positions and rotations), keeps planted feet on the ground and
// joins the T-pose transition smoothly.
#include <gtest/gtest.h>

#include "body_fixture.h"
#include "layers/core/error.h"
#include "layers/motion/procedural.h"

namespace layers::motion {
namespace {

std::vector<body::JointTransforms> track(const MotionSource& m, const body::Body& b) {
  std::vector<body::JointTransforms> t;
  for (int f = 0; f < m.num_frames(); ++f) t.push_back(body::forward_kinematics(b.skeleton, m.pose(f)));
  return t;
}

TEST(Procedural, ListsTheKinds) {
  const auto& kinds = procedural_kinds();
  for (const char* k : {"walk", "run", "turn", "spin", "jump", "step_down", "arm_raise", "wave", "squat", "hop"})
    EXPECT_NE(std::find(kinds.begin(), kinds.end(), k), kinds.end()) << k;
}

TEST(Procedural, DeterministicForASeedAndVariedAcrossSeeds) {
  const body::Body& b = body::test::body();
  for (const std::string& kind : procedural_kinds()) {
    const auto a = make_procedural(sample_procedural(kind, 60, 11), b);
    const auto c = make_procedural(sample_procedural(kind, 60, 11), b);
    const auto d = make_procedural(sample_procedural(kind, 60, 12), b);
    ASSERT_EQ(a->num_frames(), 60);
    double same = 0.0, differ = 0.0;
    for (int f = 0; f < 60; ++f) {
      const body::Pose pa = a->pose(f), pc = c->pose(f), pd = d->pose(f);
      same = std::max(same, (pa.root - pc.root).norm());
      differ = std::max(differ, (pa.root - pd.root).norm());
      for (std::size_t j = 0; j < pa.local.size(); ++j) {
        same = std::max(same, body::angle_of(pa.local[j].conjugate() * pc.local[j]));
        differ = std::max(differ, body::angle_of(pa.local[j].conjugate() * pd.local[j]));
      }
    }
    EXPECT_EQ(same, 0.0) << kind;
    EXPECT_GT(differ, 1e-3) << kind;
  }
}

TEST(Procedural, SmoothAndGrounded) {
  const body::Body& b = body::test::body();
  for (const std::string& kind : procedural_kinds()) {
    for (std::uint64_t seed : {1u, 2u}) {
      MotionSpec spec;
      spec.motion = "procedural:" + kind;
      spec.frames = 150;
      spec.seed = seed;
      spec.transition_frames = 15;
      const auto m = make_motion(spec, b);
      ASSERT_EQ(m->num_frames(), 150);
      const auto t = track(*m, b);
      double d1 = 0.0, d2 = 0.0, r2 = 0.0, lowest = 1.0;
      for (int f = 1; f + 1 < m->num_frames(); ++f) {
        for (int j = 0; j < b.skeleton.num_joints(); ++j) {
          const body::Vec3 &p0 = t[f - 1].position[j], &p1 = t[f].position[j], &p2 = t[f + 1].position[j];
          d1 = std::max(d1, (p1 - p0).norm());
          d2 = std::max(d2, (p2 - 2 * p1 + p0).norm());
          const body::Quat &q0 = t[f - 1].rotation[j], &q1 = t[f].rotation[j], &q2 = t[f + 1].rotation[j];
          r2 = std::max(r2, body::angle_of((q2 * q1.conjugate()) * (q1 * q0.conjugate()).conjugate()));
        }
        const auto soles = sole_heights(b, t[f]);
        lowest = std::min({lowest, soles[0], soles[1]});
      }
      // At 30 fps: joints move < 0.4 m per frame (12 m/s), change speed by
      // < 0.2 m per frame^2 (180 m/s^2) and turning rate by < 0.6 rad per frame^2.
      EXPECT_LT(d1, 0.4) << kind;
      EXPECT_LT(d2, 0.2) << kind;
      EXPECT_LT(r2, 0.6) << kind;
      EXPECT_GT(lowest, -0.005) << kind << ": a sole below the ground";
    }
  }
}

TEST(Procedural, PlantedFeetDoNotSlide) {
  const body::Body& b = body::test::body();
  const auto m = make_procedural(sample_procedural("walk", 150, 5), b);
  const auto t = track(*m, b);
  const body::Skeleton& sk = b.skeleton;
  const int toe[2] = {sk.require("LeftToeBase"), sk.require("RightToeBase")};
  const int foot[2] = {sk.require("LeftFoot"), sk.require("RightFoot")};
  int planted = 0;
  for (int f = 1; f < m->num_frames(); ++f) {
    const auto now = sole_heights(b, t[f]), before = sole_heights(b, t[f - 1]);
    for (int s = 0; s < 2; ++s) {
      if (now[s] > 1e-3 || before[s] > 1e-3) continue;
      // On the ground in both frames: the ball of the foot (the point on the
      // ground under the toe joint, which the heel rolls about) stays put.
      body::Vec3 ball_rest = sk.rest_head[toe[s]];
      ball_rest.y() = 0.0;
      auto ball = [&](const body::JointTransforms& x) {
        return body::Vec3(x.position[toe[s]] + x.rotation[foot[s]] * (ball_rest - sk.rest_head[toe[s]]));
      };
      const body::Vec3 a = ball(t[f - 1]), c = ball(t[f]);
      if (a.y() > 2e-4 || c.y() > 2e-4) continue;  // lifting off
      ++planted;
      EXPECT_LT((c - a).norm(), 1e-3) << "frame " << f;
    }
  }
  EXPECT_GT(planted, 60);
  // And the walk goes somewhere.
  EXPECT_GT((t.back().position[0] - t.front().position[0]).norm(), 2.0);
}

TEST(Procedural, StartsAtRestForTheTransition) {
  const body::Body& b = body::test::body();
  for (const std::string& kind : procedural_kinds()) {
    const auto m = make_procedural(sample_procedural(kind, 10, 3), b);
    const auto t = track(*m, b);
    double moved = 0.0;
    for (int j = 0; j < b.skeleton.num_joints(); ++j)
      moved = std::max(moved, (t[1].position[j] - t[0].position[j]).norm());
    EXPECT_LT(moved, 0.003) << kind;  // < 0.1 m/s at the first frame
  }
}

TEST(Procedural, RejectsUnknownKinds) {
  EXPECT_THROW(make_procedural(sample_procedural("moonwalk", 10, 0), body::test::body()), InputError);
  MotionSpec spec;
  spec.motion = "procedural:moonwalk";
  EXPECT_THROW(make_motion(spec, body::test::body()), InputError);
}

}  // namespace
}  // namespace layers::motion
