// layers/motion/bvh.h -- Biovision hierarchy (BVH) motion files.
//
// A general reader: any hierarchy, any channel order and rotation order
// per joint, End Sites, position channels on any joint. Rotation channels
// listed as "Zrotation Yrotation Xrotation" give the local rotation
// Rz * Ry * Rx (degrees in the file); a joint's local translation is its
// OFFSET plus its position channels. Malformed files raise InputError
// naming the file and line (missing MOTION block, CHANNELS count not
// matching the channel names, data lines with the wrong number of values,
// non-numeric values, frame count mismatch).
#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include "layers/body/rotation.h"

namespace layers::motion {

enum class BvhChannel { Xposition, Yposition, Zposition, Xrotation, Yrotation, Zrotation };

struct BvhJoint {
  std::string name;
  int parent = -1;
  body::Vec3 offset = body::Vec3::Zero();
  std::vector<BvhChannel> channels;
  int first_channel = 0;  // column of its first channel in a frame line
  bool has_end_site = false;
  body::Vec3 end_site = body::Vec3::Zero();  // End Site offset when present
};

struct BvhClip {
  std::string source;            // file name, for messages
  std::vector<BvhJoint> joints;  // parents before children
  double frame_time = 1.0 / 30.0;
  // Per frame, per joint: local rotation and local translation.
  std::vector<std::vector<body::Quat>> rotation;
  std::vector<std::vector<body::Vec3>> translation;

  int num_frames() const { return static_cast<int>(rotation.size()); }
  int num_joints() const { return static_cast<int>(joints.size()); }
  double fps() const { return 1.0 / frame_time; }
  int index(const std::string& name) const;  // -1 when absent
};

// Bounds of what a BVH file may declare (InputError beyond them, before
// the frames are read): at most kMaxBvhFrames frames, a frame time in
// (kMinBvhFrameTime, kMaxBvhFrameTime] seconds, kMaxBvhJoints joints,
// kMaxBvhJointFrames joints x frames (each costs 56 bytes: about 560 MB at
// the bound) and a clip of at most kMaxBvhSeconds; resample() refuses to
// make more than kMaxBvhJointFrames joints x frames either.
inline constexpr int kMaxBvhFrames = 1000000;
inline constexpr double kMinBvhFrameTime = 1e-4;
inline constexpr double kMaxBvhFrameTime = 1.0;
inline constexpr int kMaxBvhJoints = 1000;
inline constexpr long kMaxBvhJointFrames = 10000000;
inline constexpr double kMaxBvhSeconds = 3600;
BvhClip read_bvh(const std::string& path);
BvhClip parse_bvh(std::istream& in, const std::string& name);

// Resamples to `fps` over the same duration: slerp of rotations, lerp of
// translations between the two nearest source frames.
BvhClip resample(const BvhClip& clip, double fps);

struct BvhWorld {
  std::vector<body::Quat> rotation;  // world rotation per joint
  std::vector<body::Vec3> position;  // world position per joint
};

// Forward kinematics of one frame; frame = -1 gives the rest pose (all
// channels zero: identity rotations, translations = offsets).
BvhWorld bvh_world(const BvhClip& clip, int frame);

}  // namespace layers::motion
