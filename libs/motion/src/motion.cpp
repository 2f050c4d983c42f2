// Pose tracks, the T-pose transition and motion specs (see motion.h).
#include "layers/motion/motion.h"

#include <cmath>
#include <filesystem>

#include "layers/body/assets.h"
#include "layers/body/body_model.h"
#include "layers/core/error.h"
#include "layers/motion/bvh.h"
#include "layers/motion/procedural.h"
#include "layers/motion/retarget.h"

namespace layers::motion {
namespace {

constexpr int kDefaultProceduralFrames = 150;

class TransitionMotion : public MotionSource {
 public:
  TransitionMotion(std::unique_ptr<MotionSource> inner, const body::Body& body, int frames)
      : inner_(std::move(inner)), frames_(frames) {
    const body::Pose first = inner_->pose(0);
    start_ = body.t_pose;
    // Stand where the motion starts, facing its initial heading.
    const body::Vec3 forward = first.local[0] * body::Vec3::UnitZ();
    const double heading = std::atan2(forward.x(), forward.z());
    start_.local[0] = (body::rot_y(heading) * start_.local[0]).normalized();
    start_.root.x() = first.root.x();
    start_.root.z() = first.root.z();
    // The motion's frame 0 is reached at frame `frames_`.
    for (std::size_t j = 0; j < start_.local.size(); ++j)
      start_.local[j] = body::same_hemisphere(start_.local[j], first.local[j]);
    first_ = first;
  }
  int num_frames() const override { return frames_ + inner_->num_frames(); }
  body::Pose pose(int frame) const override {
    if (frame < 0 || frame >= num_frames())
      throw Error("motion frame " + std::to_string(frame) + " outside [0, " + std::to_string(num_frames()) + ")");
    if (frame >= frames_) return inner_->pose(frame - frames_);
    return body::blend(start_, first_, body::smoothstep(static_cast<double>(frame) / frames_));
  }
  std::string describe() const override { return inner_->describe(); }

 private:
  std::unique_ptr<MotionSource> inner_;
  int frames_;
  body::Pose start_, first_;
};

// Keeps the first `frames` frames of a motion.
class Truncated : public MotionSource {
 public:
  Truncated(std::unique_ptr<MotionSource> inner, int frames) : inner_(std::move(inner)), frames_(frames) {}
  int num_frames() const override { return frames_; }
  body::Pose pose(int frame) const override {
    if (frame < 0 || frame >= frames_)
      throw Error("motion frame " + std::to_string(frame) + " outside [0, " + std::to_string(frames_) + ")");
    return inner_->pose(frame);
  }
  std::string describe() const override { return inner_->describe(); }

 private:
  std::unique_ptr<MotionSource> inner_;
  int frames_;
};

bool ends_with(const std::string& s, const std::string& suffix) {
  return s.size() >= suffix.size() && s.compare(s.size() - suffix.size(), suffix.size(), suffix) == 0;
}

std::string find_bvh(const std::string& path, const std::string& asset_root) {
  namespace fs = std::filesystem;
  if (fs::exists(path)) return path;
  if (fs::path(path).is_relative()) {
    const std::string shipped = body::motion_asset_dir(asset_root) + "/" + path;
    if (fs::exists(shipped)) return shipped;
  }
  throw InputError("motion", "bvh", "an existing BVH file (or one in " + body::motion_asset_dir(asset_root) + ")",
                   "'" + path + "'");
}

}  // namespace

PoseTrack::PoseTrack(std::vector<body::Pose> poses, std::string description)
    : poses_(std::move(poses)), description_(std::move(description)) {}

body::Pose PoseTrack::pose(int frame) const {
  if (frame < 0 || frame >= num_frames())
    throw Error("motion frame " + std::to_string(frame) + " outside [0, " + std::to_string(num_frames()) + ")");
  return poses_[frame];
}

std::unique_ptr<MotionSource> with_t_pose_transition(std::unique_ptr<MotionSource> motion, const body::Body& body,
                                                     int frames) {
  if (frames <= 0) return motion;
  if (motion->num_frames() == 0) throw Error("T-pose transition into an empty motion");
  return std::make_unique<TransitionMotion>(std::move(motion), body, frames);
}

std::unique_ptr<MotionSource> make_motion(const MotionSpec& spec, const body::Body& body) {
  if (spec.frames < 0) throw InputError("motion", "frames", "0 (whole clip) or more", std::to_string(spec.frames));
  if (spec.transition_frames < 0)
    throw InputError("motion", "transition_frames", "0 or more", std::to_string(spec.transition_frames));
  if (spec.frames > 0 && spec.transition_frames >= spec.frames)
    throw InputError("motion", "transition_frames", "fewer than frames (" + std::to_string(spec.frames) + ")",
                     std::to_string(spec.transition_frames));
  const std::string& m = spec.motion;
  std::unique_ptr<MotionSource> motion;
  const int body_frames = spec.frames > 0 ? spec.frames - spec.transition_frames : 0;
  if (m.rfind("procedural:", 0) == 0) {
    const int n = body_frames > 0 ? body_frames : kDefaultProceduralFrames - spec.transition_frames;
    motion = make_procedural(sample_procedural(m.substr(11), std::max(1, n), spec.seed), body);
  } else if (m.rfind("bvh:", 0) == 0 || ends_with(m, ".bvh") || ends_with(m, ".BVH")) {
    const std::string path = find_bvh(m.rfind("bvh:", 0) == 0 ? m.substr(4) : m, spec.asset_root);
    // Recorded relative to the asset root, so a dataset does not name the
    // folder it was made in; a user's own clip elsewhere keeps its path.
    const auto track = retarget(resample(read_bvh(path), kFramesPerSecond), body);
    motion = std::make_unique<PoseTrack>(track->poses(), "bvh:" + body::asset_relative_name(path, spec.asset_root));
    if (body_frames > motion->num_frames())
      throw InputError(path, "frames",
                       "at most " + std::to_string(motion->num_frames() + spec.transition_frames) +
                           " frames (the clip at 30 fps plus the transition)",
                       std::to_string(spec.frames));
    if (body_frames > 0) motion = std::make_unique<Truncated>(std::move(motion), body_frames);
  } else {
    throw InputError("motion", "motion", "procedural:<kind>, bvh:<path> or a .bvh path", "'" + m + "'");
  }
  return with_t_pose_transition(std::move(motion), body, spec.transition_frames);
}

}  // namespace layers::motion
