// The body-and-motion config: YAML reading with errors, round trip, shape
// sampling, and the one-call generator.
#include <gtest/gtest.h>

#include "layers/core/error.h"
#include "layers/motion/body_config.h"

namespace layers::motion {
namespace {

BodyMotionConfig read(const std::string& yaml) {
  return cfg::read<BodyMotionConfig>(cfg::parse(yaml, "body.yaml"), "body");
}

TEST(BodyConfig, ReadsAndWritesBack) {
  const BodyMotionConfig c = read(
      "shape: {gender: 0.2, muscle: 0.6, weight: 0.4, height: 0.7}\n"
      "motion: procedural:run\nframes: 90\nseed: 5\ntransition_frames: 10\n"
      "on_intersection: drop\n");
  EXPECT_DOUBLE_EQ(c.shape.gender, 0.2);
  EXPECT_DOUBLE_EQ(c.shape.height, 0.7);
  EXPECT_EQ(c.motion, "procedural:run");
  EXPECT_EQ(c.frames, 90);
  EXPECT_EQ(c.seed, 5u);
  EXPECT_EQ(c.on_intersection, "drop");
  const BodyMotionConfig back = cfg::read<BodyMotionConfig>(cfg::to_node(c), "body");
  EXPECT_EQ(back.motion, c.motion);
  EXPECT_DOUBLE_EQ(back.shape.muscle, 0.6);
  EXPECT_EQ(motion_spec(c).transition_frames, 10);
  EXPECT_DOUBLE_EQ(sequence_options(c).intersection.tolerance, 0.004);
}

TEST(BodyConfig, RejectsBadValuesNamingTheKey) {
  auto expect_error = [](const std::string& yaml, const std::string& key) {
    try {
      read(yaml);
      FAIL() << "expected an error for " << key;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  expect_error("shape: {height: 1.5}\n", "body.shape.height");
  expect_error("motion: procedural:walk\nspeed: 3\n", "speed");
  expect_error("on_intersection: ignore\n", "body.on_intersection");
  expect_error("frames: -3\n", "body.frames");
}

TEST(BodyConfig, SamplesShapesWithinRanges) {
  ShapeSampling r;
  r.height = {0.4, 0.6};
  for (std::uint64_t seed = 0; seed < 50; ++seed) {
    const body::ShapeParams s = sample_shape(r, seed);
    EXPECT_GE(s.height, 0.4);
    EXPECT_LE(s.height, 0.6);
    EXPECT_GE(s.muscle, 0.25);
    EXPECT_LE(s.muscle, 0.75);
  }
  EXPECT_DOUBLE_EQ(sample_shape(r, 3).weight, sample_shape(r, 3).weight);
  EXPECT_NE(sample_shape(r, 3).gender, sample_shape(r, 4).gender);
  r.weight = {0.8, 0.2};
  EXPECT_THROW(sample_shape(r, 0), InputError);
}

TEST(BodyConfig, GeneratesABodySequence) {
  BodyMotionConfig c;
  c.motion = "procedural:squat";
  c.frames = 30;
  c.transition_frames = 10;
  const GeneratedBody g = generate_body(c);
  EXPECT_EQ(g.sequence.num_frames, 30);
  EXPECT_EQ(g.sequence.num_vertices, g.body.num_vertices());
  EXPECT_EQ(g.sequence.motion, "procedural:squat");
  EXPECT_EQ(g.sequence.intersection.remaining, 0);
}

}  // namespace
}  // namespace layers::motion
