// layers/motion/retarget.h -- BVH clips onto the body's cmu_mb skeleton.
//
// Joints are matched by name (the CMU 3dsMax-style names map onto the
// MotionBuilder-style rig names; identical names match as well). Rest
// poses are aligned per bone: the rotation taking the rig's rest bone
// direction onto the BVH's rest bone direction is applied after the BVH
// world rotation, so limb directions match frame by frame whatever the two
// rest poses are (the rig rests in an A-pose, CMU in an arms-down pose).
// Root motion is kept: the rig's hip midpoint follows the BVH hip
// midpoint scaled by the ratio of leg lengths; the clip starts above the
// origin (x, z). Ground contact: in frames where a foot is planted the
// root is moved vertically so that its sole touches y = 0 (the correction
// interpolated across airborne frames and smoothed over a few frames).
#pragma once

#include <array>
#include <map>
#include <memory>
#include <string>

#include "layers/motion/bvh.h"
#include "layers/motion/motion.h"

namespace layers::motion {

// CMU 3dsMax-friendly BVH joint names -> cmu_mb rig joint names.
const std::map<std::string, std::string>& cmu_3dsmax_names();
// CMU's ASF bone names (asf_amc.h: lfemur, lhumerus, ...) -> rig names.
const std::map<std::string, std::string>& cmu_asf_names();

// The name map a clip's joints need (BVH -> rig), by the clip's naming:
// MotionBuilder style (what Mixamo, the SFU set and our rig use: a joint
// LeftUpLeg, RightUpLeg, LeftForeArm or RightForeArm) maps names as they
// are, where LeftShoulder is the clavicle; CMU's ASF names (a bone lfemur,
// rfemur, lhumerus or rhumerus) map through cmu_asf_names(); otherwise the
// CMU 3dsMax names,
// where LeftShoulder is the upper arm. Names are read without a namespace
// prefix ("mixamorig:Hips" is Hips).
std::map<std::string, std::string> joint_name_map(const BvhClip& clip);
// A joint's name without its namespace prefix (up to the last ':').
std::string bare_joint_name(const std::string& name);

struct RetargetOptions {
  std::map<std::string, std::string> names;  // BVH (bare names) -> rig; empty: joint_name_map(clip)
  bool start_at_origin = true;               // move the first frame's root above (0, 0)
  bool ground = true;                        // lift the clip so the soles touch y = 0 in stance
};

// Which feet touch the ground, per frame: a foot is planted when its heel
// (ankle joint) or ball (toe joint) moves slower than 0.25 m/s
// horizontally and its sole is within 10 cm of the clip's lowest sole.
struct FootContacts {
  std::vector<std::array<double, 2>> sole_height;  // lowest sole point, left / right
  std::vector<std::array<bool, 2>> planted;
};
FootContacts foot_contacts(const body::Body& body, const std::vector<body::Pose>& poses);

// The rig joints retargeting places the legs and feet with (besides the
// root): a rig without one of them cannot take a clip.
inline constexpr const char* kRetargetLegJoints[] = {"LeftUpLeg",  "LeftLeg",  "LeftFoot",  "LeftToeBase",
                                                     "RightUpLeg", "RightLeg", "RightFoot", "RightToeBase"};

// `clip` should already be at 30 fps (see resample()).
std::unique_ptr<PoseTrack> retarget(const BvhClip& clip, const body::Body& body, const RetargetOptions& options = {});

}  // namespace layers::motion
