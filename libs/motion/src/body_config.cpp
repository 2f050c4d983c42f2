// Shape sampling and the one-call body generator (see body_config.h).
#include "layers/motion/body_config.h"

#include <random>

#include "layers/core/error.h"

namespace layers::motion {

body::ShapeParams sample_shape(const ShapeSampling& ranges, std::uint64_t seed) {
  std::mt19937_64 gen(seed ^ 0xB0D1E5ull);
  auto draw = [&](const std::vector<double>& r, const char* name) {
    if (r.size() != 2 || !(r[0] <= r[1]) || r[0] < 0.0 || r[1] > 1.0)
      throw InputError("shape sampling", name, "[lo, hi] with 0 <= lo <= hi <= 1",
                       std::to_string(r.size()) + " numbers");
    return std::uniform_real_distribution<double>(r[0], std::nextafter(r[1], 2.0))(gen);
  };
  body::ShapeParams s;
  s.gender = std::min(1.0, draw(ranges.gender, "gender"));
  s.muscle = std::min(1.0, draw(ranges.muscle, "muscle"));
  s.weight = std::min(1.0, draw(ranges.weight, "weight"));
  s.height = std::min(1.0, draw(ranges.height, "height"));
  return s;
}

MotionSpec motion_spec(const BodyMotionConfig& config) {
  MotionSpec m;
  m.motion = config.motion;
  m.frames = config.frames;
  m.seed = config.seed;
  m.transition_frames = config.transition_frames;
  m.asset_root = config.assets;
  return m;
}

SequenceOptions sequence_options(const BodyMotionConfig& config) {
  SequenceOptions o;
  o.intersection.tolerance = config.intersection_tolerance_mm / 1000.0;
  o.intersection.gap = config.self_gap_mm / 1000.0;
  o.arm_room = config.arm_room_mm / 1000.0;
  o.thigh_room = config.thigh_room_mm / 1000.0;
  o.skin_untangle = config.skin_untangle.options();
  o.on_intersection = config.on_intersection;
  return o;
}

GeneratedBody generate_body(const BodyMotionConfig& config) {
  auto model = body::BodyModel::load(config.assets);
  GeneratedBody out{model->build(config.shape), {}};
  auto motion = make_motion(motion_spec(config), out.body);
  out.sequence = generate_body_sequence(out.body, *motion, sequence_options(config));
  return out;
}

}  // namespace layers::motion
