// layers/motion/motion.h -- a motion: a function from frame index (30 fps)
// to a Pose of the body's skeleton (local joint rotations relative to the
// rest pose + root position; see skeleton.h). Retargeted BVH clips and
// procedural motions both implement MotionSource; make_motion() builds one
// from a spec string, optionally preceded by a smooth transition from the
// T-pose.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "layers/body/skeleton.h"

namespace layers::body {
struct Body;
}  // namespace layers::body

namespace layers::motion {

constexpr double kFramesPerSecond = 30.0;

class MotionSource {
 public:
  virtual ~MotionSource() = default;
  virtual int num_frames() const = 0;
  // 0 <= frame < num_frames(); throws layers::Error outside.
  virtual body::Pose pose(int frame) const = 0;
  // What it is, for logs and the `motion` attribute (e.g. "procedural:walk").
  virtual std::string describe() const = 0;
};

// A motion stored as one pose per frame.
class PoseTrack : public MotionSource {
 public:
  PoseTrack(std::vector<body::Pose> poses, std::string description);
  int num_frames() const override { return static_cast<int>(poses_.size()); }
  body::Pose pose(int frame) const override;
  std::string describe() const override { return description_; }
  const std::vector<body::Pose>& poses() const { return poses_; }

 private:
  std::vector<body::Pose> poses_;
  std::string description_;
};

// Prepends `frames` frames that blend from the body's T-pose (standing
// where the motion starts, soles on the ground) into the motion's first
// pose with a C1 (smoothstep) ramp; the motion follows unchanged.
std::unique_ptr<MotionSource> with_t_pose_transition(std::unique_ptr<MotionSource> motion, const body::Body& body,
                                                     int frames);

struct MotionSpec {
  // "procedural:<kind>" (see procedural_kinds()), "bvh:<path>" or a path
  // ending in .bvh. A relative BVH path that does not exist is also looked
  // up in the asset folder's motions/ (the shipped clips are cmu/<clip>.bvh).
  // Either may be followed by parameters, as describe() writes them:
  // procedural ones (procedural.h: speed=, amplitude=, phase=, ...), and
  // for clips "window=<start>+<frames>" (clip frames at 30 fps; see
  // clip_window()) and "mirror=0|1" (clip_ops.h). With any of them the
  // description lists all of them, so it identifies the motion exactly.
  std::string motion = "procedural:walk";
  int frames = 0;             // 0: the clip's length (BVH) or 150 (procedural)
  std::uint64_t seed = 0;     // randomises procedural speed / amplitude
  int transition_frames = 0;  // T-pose transition prepended (0: none)
  std::string asset_root;     // "" = default_asset_root()
};

// Builds the motion for `body`; the result has exactly spec.frames frames
// when spec.frames > 0 (a BVH clip shorter than that is an InputError).
// Bad specs and unreadable files raise InputError naming them.
std::unique_ptr<MotionSource> make_motion(const MotionSpec& spec, const body::Body& body);

// The BVH file a spec's path names (as above); InputError when none exists.
std::string find_bvh_file(const std::string& path, const std::string& asset_root = "");

// A motion library: when `entry` (optionally "bvh:"-prefixed) names a
// folder, here or inside the motion asset folder, the clip files in it
// (.bvh, or .amc with its skeleton beside it), named as `entry` names the
// folder and sorted by name; not sub-folders. Empty when `entry` is not a
// folder; InputError naming `where` when the folder holds no clip.
std::vector<std::string> clip_folder_entries(const std::string& entry, const std::string& where,
                                             const std::string& asset_root = "");

}  // namespace layers::motion
