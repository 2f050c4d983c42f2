// Pose tracks, the T-pose transition and motion specs (see motion.h).
#include "layers/motion/motion.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "layers/body/assets.h"
#include "layers/body/body_model.h"
#include "layers/core/error.h"
#include "layers/motion/asf_amc.h"
#include "layers/motion/bvh.h"
#include "layers/motion/clip_ops.h"
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

// A clip spec split into its path and its window / mirror parameters.
struct ClipSpec {
  std::string path;
  bool explicit_params = false;
  int start = 0, length = 0;  // length 0: not given
  bool mirror = false;
};

ClipSpec parse_clip(const std::string& text) {
  ClipSpec c;
  c.path = text;
  // Parameters are trailing " key=value" tokens (a path may hold spaces).
  while (true) {
    const auto space = c.path.find_last_of(' ');
    if (space == std::string::npos) break;
    const std::string token = c.path.substr(space + 1);
    const auto eq = token.find('=');
    const std::string key = token.substr(0, eq == std::string::npos ? 0 : eq);
    if (key != "window" && key != "mirror") break;
    const std::string value = token.substr(eq + 1);
    if (key == "mirror") {
      if (value != "0" && value != "1") throw InputError("motion", "mirror", "0 or 1", "'" + value + "'");
      c.mirror = value == "1";
    } else {
      const auto plus = value.find('+');
      std::size_t a = 0, b = 0;
      try {
        c.start = std::stoi(value.substr(0, plus), &a);
        c.length = plus == std::string::npos ? 0 : std::stoi(value.substr(plus + 1), &b);
      } catch (const std::exception&) {
        a = 0;
      }
      if (plus == std::string::npos || a != plus || b != value.size() - plus - 1 || c.start < 0 || c.length < 1)
        throw InputError("motion", "window", "<start>+<frames> (clip frames at 30 fps, start >= 0, frames >= 1)",
                         "'" + value + "'");
    }
    c.explicit_params = true;
    c.path.erase(space);
  }
  return c;
}

}  // namespace

std::string find_bvh_file(const std::string& path, const std::string& asset_root) {
  namespace fs = std::filesystem;
  if (fs::exists(path)) return path;
  if (fs::path(path).is_relative()) {
    const std::string shipped = body::motion_asset_dir(asset_root) + "/" + path;
    if (fs::exists(shipped)) return shipped;
  }
  throw InputError("motion", "bvh",
                   "an existing clip file, .bvh or .amc (or one in " + body::motion_asset_dir(asset_root) + ")",
                   "'" + path + "'");
}

std::vector<std::string> clip_folder_entries(const std::string& entry, const std::string& where,
                                             const std::string& asset_root) {
  namespace fs = std::filesystem;
  const bool prefixed = entry.rfind("bvh:", 0) == 0;
  const std::string named = prefixed ? entry.substr(4) : entry;
  if (named.empty() || named.find(' ') != std::string::npos) return {};
  fs::path folder = named;
  std::error_code ec;
  if (!fs::is_directory(folder, ec)) {
    if (!folder.is_relative()) return {};
    folder = fs::path(body::motion_asset_dir(asset_root)) / named;
    if (!fs::is_directory(folder, ec)) return {};
  }
  std::vector<std::string> names;
  for (const fs::directory_entry& e : fs::directory_iterator(folder, ec))
    if (e.is_regular_file(ec) && is_clip_file(e.path().string())) names.push_back(e.path().filename().string());
  if (ec) throw InputError(where, "'" + entry + "'", "a readable folder of clips", ec.message());
  if (names.empty())
    throw InputError(where, "'" + entry + "'", "a folder holding at least one .bvh or .amc clip", "none in it");
  std::sort(names.begin(), names.end());
  std::string base = named;
  while (base.size() > 1 && base.back() == '/') base.pop_back();
  for (std::string& n : names) n = (prefixed ? "bvh:" : "") + base + "/" + n;
  return names;
}

namespace {

// A retargeted clip, optionally mirrored and windowed (see MotionSpec).
std::unique_ptr<MotionSource> make_clip(const ClipSpec& clip, const MotionSpec& spec, int body_frames,
                                        const body::Body& body) {
  const std::string path = find_bvh_file(clip.path, spec.asset_root);
  // Recorded relative to the asset root, so a dataset does not name the
  // folder it was made in; a user's own clip elsewhere keeps its path.
  const auto track = retarget(resample(read_clip(path), kFramesPerSecond), body);
  const std::string name = "bvh:" + body::asset_relative_name(path, spec.asset_root);
  const int clip_frames = track->num_frames();
  if (!clip.explicit_params) {
    std::unique_ptr<MotionSource> motion = std::make_unique<PoseTrack>(track->poses(), name);
    if (body_frames > clip_frames)
      throw InputError(path, "frames",
                       "at most " + std::to_string(clip_frames + spec.transition_frames) +
                           " frames (the clip at 30 fps plus the transition)",
                       std::to_string(spec.frames));
    if (body_frames > 0) motion = std::make_unique<Truncated>(std::move(motion), body_frames);
    return motion;
  }
  const int length = clip.length > 0 ? clip.length : body_frames > 0 ? body_frames : clip_frames - clip.start;
  if (body_frames > 0 && length != body_frames)
    throw InputError("motion", "window",
                     std::to_string(body_frames) + " frames (the motion's frames less the transition)",
                     std::to_string(length));
  if (clip.start + length > clip_frames)
    throw InputError(path, "window", "a window inside the clip's " + std::to_string(clip_frames) + " frames at 30 fps",
                     std::to_string(clip.start) + "+" + std::to_string(length));
  std::vector<body::Pose> poses = track->poses();
  if (clip.mirror) {
    const PoseMirror mirror(body.skeleton);
    for (body::Pose& p : poses) p = mirror(p);
  }
  return std::make_unique<PoseTrack>(clip_window(poses, clip.start, length),
                                     name + " window=" + std::to_string(clip.start) + "+" + std::to_string(length) +
                                         " mirror=" + (clip.mirror ? "1" : "0"));
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
  const ClipSpec clip = parse_clip(m);
  if (m.rfind("procedural:", 0) == 0) {
    const int n = body_frames > 0 ? body_frames : kDefaultProceduralFrames - spec.transition_frames;
    motion = make_procedural(parse_procedural(m.substr(11), std::max(1, n), spec.seed, "motion"), body);
  } else if (clip.path.rfind("bvh:", 0) == 0 || is_clip_file(clip.path)) {
    ClipSpec named = clip;
    if (named.path.rfind("bvh:", 0) == 0) named.path = named.path.substr(4);
    motion = make_clip(named, spec, body_frames, body);
  } else {
    throw InputError("motion", "motion", "procedural:<kind>, bvh:<path>, a .bvh path or a .amc path (ASF/AMC)",
                     "'" + m + "'");
  }
  return with_t_pose_transition(std::move(motion), body, spec.transition_frames);
}

}  // namespace layers::motion
