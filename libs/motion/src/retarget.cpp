// Name map, rest-pose alignment, root scaling and grounding of BVH clips
// (see retarget.h).
#include "layers/motion/retarget.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>

#include "layers/body/body_model.h"
#include "layers/body/skinning.h"
#include "layers/core/error.h"
#include "smoothing.h"

namespace layers::motion {
namespace {

constexpr double kMinBone = 0.01;  // BVH segments shorter than this (m, scaled) carry no direction

// The limb bones whose lengths must be in the rig's proportion, and the
// allowed ratio (clip over rig, the clip scaled by leg length).
constexpr const char* kRetargetLimbs[] = {"LeftArm",   "LeftForeArm", "RightArm",   "RightForeArm",
                                          "LeftUpLeg", "LeftLeg",     "RightUpLeg", "RightLeg"};
constexpr double kLimbRatio[2] = {0.6, 1.6};
constexpr double kMaxHipLineDegrees = 20;

constexpr double kGroundSmoothing = 1.5;  // frames (Gaussian sigma) for the ground correction
constexpr double kContactSpeed = 0.25;    // m/s: a foot whose heel or ball moves slower is planted
constexpr double kContactHeight = 0.10;   // m above the lowest sole of the clip

// The world point of the BVH rest pose that corresponds to the tail of rig
// bone r: the BVH joint of the rig child whose head is r's tail (or, when
// the clip lacks that joint, of the first joint down the rig chain from it
// that it has; walking down the BVH chain past zero-length segments), else
// an End Site or a child of r's BVH joint. False when there is none.
bool bvh_tail_point(const BvhClip& clip, const BvhWorld& rest, const body::Skeleton& sk, const std::vector<int>& to_bvh,
                    int r, body::Vec3& out) {
  const int b = to_bvh[r];
  const body::Vec3& head = rest.position[b];
  for (int c : sk.children(r)) {
    if ((sk.rest_head[c] - sk.rest_tail[r]).norm() > 1e-4) continue;
    // A rig joint the clip lacks there (a lower back): the chain on from it.
    int m = c;
    while (m >= 0 && to_bvh[m] < 0) {
      int next = -1;
      for (int g : sk.children(m))
        if ((sk.rest_head[g] - sk.rest_tail[m]).norm() <= 1e-4) {
          next = g;
          break;
        }
      m = next;
    }
    if (m < 0) continue;
    int j = to_bvh[m];
    while (j >= 0) {
      if ((rest.position[j] - head).norm() > kMinBone) {
        out = rest.position[j];
        return true;
      }
      int next = -1;
      for (int k = 0; k < clip.num_joints(); ++k)
        if (clip.joints[k].parent == j) {
          next = k;
          break;
        }
      if (next < 0 && clip.joints[j].has_end_site) {
        out = rest.position[j] + clip.joints[j].end_site;
        return (out - head).norm() > kMinBone;
      }
      j = next;
    }
  }
  if (clip.joints[b].has_end_site && clip.joints[b].end_site.norm() > kMinBone) {
    out = head + clip.joints[b].end_site;
    return true;
  }
  for (int k = 0; k < clip.num_joints(); ++k)
    if (clip.joints[k].parent == b && (rest.position[k] - head).norm() > kMinBone) {
      out = rest.position[k];
      return true;
    }
  return false;
}

double leg_length(const std::vector<body::Vec3>& p, int hip, int knee, int ankle) {
  return (p[knee] - p[hip]).norm() + (p[ankle] - p[knee]).norm();
}

// Hip, knee and ankle joints of the left and right leg.
std::array<std::array<int, 3>, 2> leg_chains(const body::Skeleton& sk) {
  return {{{sk.require("LeftUpLeg"), sk.require("LeftLeg"), sk.require("LeftFoot")},
           {sk.require("RightUpLeg"), sk.require("RightLeg"), sk.require("RightFoot")}}};
}

// Per frame, how far the root must drop so that every planted foot's leg
// can reach the ground (at 99.5% of its length).
std::vector<double> root_drop_for_reach(const body::Body& body, const std::vector<body::Pose>& poses,
                                        const FootContacts& c) {
  const body::Skeleton& sk = body.skeleton;
  const auto chains = leg_chains(sk);
  std::vector<double> drop(poses.size(), 0.0);
  for (std::size_t f = 0; f < poses.size(); ++f) {
    if (!c.planted[f][0] && !c.planted[f][1]) continue;
    const body::JointTransforms t = body::forward_kinematics(sk, poses[f]);
    for (int s = 0; s < 2; ++s) {
      if (!c.planted[f][s] || c.sole_height[f][s] <= 0.0) continue;
      const body::Vec3 hip = t.position[chains[s][0]];
      const body::Vec3 ankle = t.position[chains[s][2]] - body::Vec3(0.0, c.sole_height[f][s], 0.0);
      const double reach = 0.995 * (sk.bone_length(chains[s][0]) + sk.bone_length(chains[s][1]));
      const body::Vec3 d = hip - ankle;
      const double horizontal2 = d.x() * d.x() + d.z() * d.z();
      if (d.squaredNorm() <= reach * reach || horizontal2 >= reach * reach) continue;
      drop[f] = std::max(drop[f], d.y() - std::sqrt(reach * reach - horizontal2));
    }
  }
  return drop;
}

// Moves the ankle of joint chain (hip, knee, ankle) by `lift` vertically
// (two-bone IK keeping the knee's bending plane), keeping the foot's world
// orientation; updates the world rotations in `world`.
void lift_ankle(const body::JointTransforms& t, std::vector<body::Quat>& world, int hip, int knee, int ankle,
                double lift) {
  const body::Vec3 h = t.position[hip], k = t.position[knee], a = t.position[ankle];
  const double l1 = (k - h).norm(), l2 = (a - k).norm();
  const body::Vec3 target = a + body::Vec3(0.0, lift, 0.0);
  body::Vec3 d = target - h;
  const double dist = std::clamp(d.norm(), std::abs(l1 - l2) + 1e-4, 0.9995 * (l1 + l2));
  d.normalize();
  // Bending plane: the current knee direction off the hip-ankle line.
  body::Vec3 pole = (k - h) - (k - h).dot(d) * d;
  if (pole.norm() < 1e-9)
    pole = (t.rotation[0] * body::Vec3::UnitZ()) - (t.rotation[0] * body::Vec3::UnitZ()).dot(d) * d;
  pole.normalize();
  const double cos_hip = std::clamp((l1 * l1 + dist * dist - l2 * l2) / (2 * l1 * dist), -1.0, 1.0);
  const body::Vec3 new_knee = h + l1 * (cos_hip * d + std::sqrt(1.0 - cos_hip * cos_hip) * pole);
  const body::Vec3 new_ankle = h + dist * d;
  const body::Quat foot = world[ankle];
  world[hip] = (body::shortest_arc(k - h, new_knee - h) * world[hip]).normalized();
  world[knee] = (body::shortest_arc(a - k, new_ankle - new_knee) * world[knee]).normalized();
  world[ankle] = foot;
}

void plant_feet(const body::Body& body, std::vector<body::Pose>& poses, const FootContacts& contacts) {
  const body::Skeleton& sk = body.skeleton;
  const int n = static_cast<int>(poses.size());
  const auto chains = leg_chains(sk);
  // The lift of a planted foot; across its swing the lift is interpolated
  // between the stances around it, so smoothing does not weaken contacts.
  std::array<std::vector<double>, 2> lift;
  for (int s = 0; s < 2; ++s) {
    lift[s].assign(n, std::numeric_limits<double>::quiet_NaN());
    for (int f = 0; f < n; ++f)
      if (contacts.planted[f][s]) lift[s][f] = -contacts.sole_height[f][s];
    fill_gaps(lift[s], 0.0);
    lift[s] = gaussian_smooth(lift[s], kGroundSmoothing);
  }
  for (int f = 0; f < n; ++f) {
    if (std::abs(lift[0][f]) < 1e-4 && std::abs(lift[1][f]) < 1e-4) continue;
    const body::JointTransforms t = body::forward_kinematics(sk, poses[f]);
    std::vector<body::Quat> world = t.rotation;
    for (int s = 0; s < 2; ++s)
      if (std::abs(lift[s][f]) >= 1e-4) lift_ankle(t, world, chains[s][0], chains[s][1], chains[s][2], lift[s][f]);
    // Children of the changed joints keep their local rotations.
    for (int j = 0; j < sk.num_joints(); ++j) {
      const bool changed = j == chains[0][0] || j == chains[0][1] || j == chains[0][2] || j == chains[1][0] ||
                           j == chains[1][1] || j == chains[1][2];
      if (!changed && sk.parents[j] >= 0) world[j] = world[sk.parents[j]] * poses[f].local[j];
    }
    poses[f] = body::pose_from_world(sk, world, poses[f].root);
  }
}

}  // namespace

FootContacts foot_contacts(const body::Body& body, const std::vector<body::Pose>& poses) {
  const body::Skeleton& sk = body.skeleton;
  const int heel[2] = {sk.require("LeftFoot"), sk.require("RightFoot")};
  const int ball[2] = {sk.require("LeftToeBase"), sk.require("RightToeBase")};
  const int n = static_cast<int>(poses.size());
  FootContacts c;
  c.sole_height.resize(n);
  c.planted.resize(n);
  std::vector<body::JointTransforms> t;
  t.reserve(n);
  double lowest = std::numeric_limits<double>::infinity();
  for (int f = 0; f < n; ++f) {
    t.push_back(body::forward_kinematics(sk, poses[f]));
    c.sole_height[f] = sole_heights(body, t.back());
    lowest = std::min({lowest, c.sole_height[f][0], c.sole_height[f][1]});
  }
  auto speed = [&](int f, int joint) {
    const int a = std::max(0, f - 1), b = std::min(n - 1, f + 1);
    if (a == b) return 0.0;
    body::Vec3 d = t[b].position[joint] - t[a].position[joint];
    d.y() = 0.0;
    return d.norm() * kFramesPerSecond / (b - a);
  };
  for (int f = 0; f < n; ++f)
    for (int s = 0; s < 2; ++s)
      c.planted[f][s] = std::min(speed(f, heel[s]), speed(f, ball[s])) < kContactSpeed &&
                        c.sole_height[f][s] < lowest + kContactHeight;
  return c;
}

const std::map<std::string, std::string>& cmu_3dsmax_names() {
  static const std::map<std::string, std::string> names = {
      {"Hips", "Hips"},
      {"LHipJoint", "LHipJoint"},
      {"LeftHip", "LeftUpLeg"},
      {"LeftKnee", "LeftLeg"},
      {"LeftAnkle", "LeftFoot"},
      {"LeftToe", "LeftToeBase"},
      {"RHipJoint", "RHipJoint"},
      {"RightHip", "RightUpLeg"},
      {"RightKnee", "RightLeg"},
      {"RightAnkle", "RightFoot"},
      {"RightToe", "RightToeBase"},
      {"lowerback", "LowerBack"},
      {"Chest", "Spine"},
      {"Chest2", "Spine1"},
      {"lowerneck", "Neck"},
      {"Neck", "Neck1"},
      {"Head", "Head"},
      {"LeftCollar", "LeftShoulder"},
      {"LeftShoulder", "LeftArm"},
      {"LeftElbow", "LeftForeArm"},
      {"LeftWrist", "LeftHand"},
      {"lhand", "LeftFingerBase"},
      {"LFingers", "LeftHandFinger1"},
      {"LThumb", "LThumb"},
      {"RightCollar", "RightShoulder"},
      {"RightShoulder", "RightArm"},
      {"RightElbow", "RightForeArm"},
      {"RightWrist", "RightHand"},
      {"rhand", "RightFingerBase"},
      {"RFingers", "RightHandFinger1"},
      {"RThumb", "RThumb"},
  };
  return names;
}

const std::map<std::string, std::string>& cmu_asf_names() {
  static const std::map<std::string, std::string> names = {
      {"root", "Hips"},
      {"lhipjoint", "LHipJoint"},
      {"lfemur", "LeftUpLeg"},
      {"ltibia", "LeftLeg"},
      {"lfoot", "LeftFoot"},
      {"ltoes", "LeftToeBase"},
      {"rhipjoint", "RHipJoint"},
      {"rfemur", "RightUpLeg"},
      {"rtibia", "RightLeg"},
      {"rfoot", "RightFoot"},
      {"rtoes", "RightToeBase"},
      {"lowerback", "LowerBack"},
      {"upperback", "Spine"},
      {"thorax", "Spine1"},
      {"lowerneck", "Neck"},
      {"upperneck", "Neck1"},
      {"head", "Head"},
      {"lclavicle", "LeftShoulder"},
      {"lhumerus", "LeftArm"},
      {"lradius", "LeftForeArm"},
      {"lwrist", "LeftHand"},
      {"lhand", "LeftFingerBase"},
      {"lfingers", "LeftHandFinger1"},
      {"lthumb", "LThumb"},
      {"rclavicle", "RightShoulder"},
      {"rhumerus", "RightArm"},
      {"rradius", "RightForeArm"},
      {"rwrist", "RightHand"},
      {"rhand", "RightFingerBase"},
      {"rfingers", "RightHandFinger1"},
      {"rthumb", "RThumb"},
  };
  return names;
}

std::string bare_joint_name(const std::string& name) {
  const auto colon = name.rfind(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

std::map<std::string, std::string> joint_name_map(const BvhClip& clip) {
  for (const BvhJoint& j : clip.joints) {
    const std::string name = bare_joint_name(j.name);
    if (name == "LeftUpLeg" || name == "RightUpLeg" || name == "LeftForeArm" || name == "RightForeArm") return {};
    if (name == "lfemur" || name == "rfemur" || name == "lhumerus" || name == "rhumerus") return cmu_asf_names();
  }
  return cmu_3dsmax_names();
}

std::unique_ptr<PoseTrack> retarget(const BvhClip& clip, const body::Body& body, const RetargetOptions& options) {
  const body::Skeleton& sk = body.skeleton;
  const int nr = sk.num_joints();
  if (clip.num_frames() == 0) throw InputError::message(clip.source, "MOTION", "the clip has no frames");

  // Rig joint -> BVH joint: through the name map, else the same name.
  const std::map<std::string, std::string> names = options.names.empty() ? joint_name_map(clip) : options.names;
  std::vector<int> to_bvh(nr, -1);
  for (int b = 0; b < clip.num_joints(); ++b) {
    const std::string bare = bare_joint_name(clip.joints[b].name);
    auto it = names.find(bare);
    const std::string& rig_name = it != names.end() ? it->second : bare;
    int r = sk.index(rig_name);
    if (r >= 0 && to_bvh[r] < 0) to_bvh[r] = b;
  }
  if (to_bvh[0] < 0)
    throw InputError(clip.source, "HIERARCHY", "a joint that maps onto the rig root '" + sk.names[0] + "'", "none");
  // At least half of the joints the two skeletons could share match (a
  // user's rig may have many more joints than the clip: fingers, twists).
  int mapped = static_cast<int>(std::count_if(to_bvh.begin(), to_bvh.end(), [](int b) { return b >= 0; }));
  const int shareable = std::min(nr, clip.num_joints());
  if (mapped < shareable / 2)
    throw InputError(clip.source, "HIERARCHY", "joint names of the CMU skeleton (3dsMax or MotionBuilder style)",
                     std::to_string(mapped) + " of " + std::to_string(shareable) + " joints matched");

  // Rest alignment per rig bone.
  const BvhWorld rest = bvh_world(clip, -1);
  std::vector<body::Quat> align(nr, body::Quat::Identity());
  for (int r = 0; r < nr; ++r) {
    if (to_bvh[r] < 0) continue;
    body::Vec3 tail;
    const body::Vec3 rig_dir = sk.rest_tail[r] - sk.rest_head[r];
    if (!bvh_tail_point(clip, rest, sk, to_bvh, r, tail) || rig_dir.norm() < 1e-6) continue;
    const body::Vec3 bvh_dir = tail - rest.position[to_bvh[r]];
    align[r] = body::shortest_arc(rig_dir, bvh_dir);
  }
  // The root also needs its heading: align the hip line as well.
  const int lh = sk.index("LeftUpLeg"), rh = sk.index("RightUpLeg");
  if (lh >= 0 && rh >= 0 && to_bvh[lh] >= 0 && to_bvh[rh] >= 0) {
    body::Vec3 rig_side = sk.rest_head[lh] - sk.rest_head[rh];
    body::Vec3 bvh_side = rest.position[to_bvh[lh]] - rest.position[to_bvh[rh]];
    body::Vec3 rig_up = sk.rest_tail[0] - sk.rest_head[0];
    body::Vec3 bvh_up = align[0] * rig_up;
    if (rig_side.norm() > 1e-6 && bvh_side.norm() > 1e-6) align[0] = body::aim(rig_up, rig_side, bvh_up, bvh_side);
  }

  // Root scale: rig leg length over BVH leg length.
  double scale = 1.0;
  const int lk = sk.index("LeftLeg"), la = sk.index("LeftFoot");
  if (lh >= 0 && lk >= 0 && la >= 0 && to_bvh[lh] >= 0 && to_bvh[lk] >= 0 && to_bvh[la] >= 0) {
    double bvh_leg = leg_length(rest.position, to_bvh[lh], to_bvh[lk], to_bvh[la]);
    if (bvh_leg > 1e-6) scale = leg_length(sk.rest_head, lh, lk, la) / bvh_leg;
  }

  // Faithfulness, 1: each limb bone of the clip, scaled by the leg ratio,
  // in the rig's proportion (a name map that puts the clavicle on the
  // upper arm makes it about twice as long; real actors stay within 0.8-1.3).
  for (const char* limb : kRetargetLimbs) {
    const int r = sk.index(limb);
    if (r < 0 || to_bvh[r] < 0) continue;
    for (int c : sk.children(r)) {
      if (to_bvh[c] < 0 || (sk.rest_head[c] - sk.rest_tail[r]).norm() > 1e-4) continue;
      const double rig = (sk.rest_tail[r] - sk.rest_head[r]).norm();
      const double bvh = scale * (rest.position[to_bvh[c]] - rest.position[to_bvh[r]]).norm();
      if (rig > 1e-6 && (bvh < kLimbRatio[0] * rig || bvh > kLimbRatio[1] * rig)) {
        char ratio[32];
        std::snprintf(ratio, sizeof ratio, "%.2f", bvh / rig);
        throw InputError(clip.source, "HIERARCHY",
                         "limbs in the rig's proportions (upper arm, forearm, thigh and shin 0.6-1.6 times the rig's "
                         "when scaled by leg length; otherwise the joint names were not understood)",
                         "rig bone " + sk.names[r] + " -> " + sk.names[c] + " " + ratio + " times, from the clip's " +
                             clip.joints[to_bvh[r]].name + " -> " + clip.joints[to_bvh[c]].name);
      }
    }
  }

  // The root follows the BVH hip midpoint (scaled), so the legs hang from
  // the same place whatever the root-to-hip offsets of the two skeletons.
  const int bl = to_bvh[lh], br = to_bvh[rh];
  auto bvh_anchor = [&](const BvhWorld& w) {
    return bl >= 0 && br >= 0 ? body::Vec3(0.5 * (w.position[bl] + w.position[br])) : w.position[to_bvh[0]];
  };
  const body::Vec3 rig_anchor =
      bl >= 0 && br >= 0 ? body::Vec3(0.5 * (sk.rest_head[lh] + sk.rest_head[rh])) : sk.rest_head[0];
  const body::Vec3 anchor_offset = rig_anchor - sk.rest_head[0];

  std::vector<body::Pose> poses;
  poses.reserve(clip.num_frames());
  const body::Vec3 start = scale * bvh_anchor(bvh_world(clip, 0));
  for (int f = 0; f < clip.num_frames(); ++f) {
    const BvhWorld w = bvh_world(clip, f);
    std::vector<body::Quat> world(nr);
    for (int r = 0; r < nr; ++r) {
      if (to_bvh[r] >= 0)
        world[r] = (w.rotation[to_bvh[r]] * align[r]).normalized();
      else
        world[r] = r == 0 ? body::Quat::Identity() : world[sk.parents[r]];
    }
    body::Vec3 root = scale * bvh_anchor(w) - world[0] * anchor_offset;
    if (options.start_at_origin) {
      root.x() -= start.x();
      root.z() -= start.z();
    }
    body::Pose pose = body::pose_from_world(sk, world, root);
    // Keep quaternion tracks continuous for later interpolation.
    if (!poses.empty())
      for (int r = 0; r < nr; ++r) pose.local[r] = body::same_hemisphere(pose.local[r], poses.back().local[r]);
    poses.push_back(std::move(pose));
  }

  // Faithfulness, 2: the pelvis faces the clip's way (the hip line within
  // kMaxHipLineDegrees of the clip's) in the first, middle and last frames.
  if (bl >= 0 && br >= 0) {
    const int n = static_cast<int>(poses.size());
    for (int f : {0, n / 2, n - 1}) {
      const body::JointTransforms t = body::forward_kinematics(sk, poses[f]);
      const BvhWorld w = bvh_world(clip, f);
      const body::Vec3 rig = t.position[lh] - t.position[rh], bvh = w.position[bl] - w.position[br];
      const double cosine = rig.normalized().dot(bvh.normalized());
      if (rig.norm() > 1e-6 && bvh.norm() > 1e-9 && !(cosine >= std::cos(kMaxHipLineDegrees * M_PI / 180))) {
        char angle[32];
        std::snprintf(angle, sizeof angle, "%.0f", std::acos(std::clamp(cosine, -1.0, 1.0)) * 180 / M_PI);
        throw InputError(clip.source, "HIERARCHY",
                         "a skeleton the rig can follow (its hip line within 20 degrees of the clip's)",
                         std::string("the hip line ") + angle + " degrees off in frame " + std::to_string(f));
      }
    }
  }

  if (options.ground) {
    // Per frame, the height of the soles of the feet in contact; the root
    // is moved vertically so they touch y = 0, the correction interpolated
    // across frames without contact (flight keeps its arc) and smoothed.
    const FootContacts contacts = foot_contacts(body, poses);
    const int n = static_cast<int>(poses.size());
    std::vector<double> offset(n, std::numeric_limits<double>::quiet_NaN());
    for (int f = 0; f < n; ++f) {
      double h = std::numeric_limits<double>::infinity();
      for (int s = 0; s < 2; ++s)
        if (contacts.planted[f][s]) h = std::min(h, contacts.sole_height[f][s]);
      if (std::isfinite(h)) offset[f] = -h;
    }
    fill_gaps(offset, -std::min(contacts.sole_height[0][0], contacts.sole_height[0][1]));
    const std::vector<double> smooth = gaussian_smooth(offset, kGroundSmoothing);
    for (int f = 0; f < n; ++f) poses[f].root.y() += smooth[f];
    // The root puts the lowest planted sole on the ground; a second planted
    // foot that floats or sinks (the leg proportions differ from the
    // actor's) is brought to the ground by leg IK, the root lowered further
    // where that leg is too short.
    FootContacts after = foot_contacts(body, poses);
    const std::vector<double> drop = upper_envelope(root_drop_for_reach(body, poses, after), kGroundSmoothing);
    for (int f = 0; f < n; ++f) poses[f].root.y() -= drop[f];
    plant_feet(body, poses, foot_contacts(body, poses));
  }
  return std::make_unique<PoseTrack>(std::move(poses), "bvh:" + clip.source);
}

}  // namespace layers::motion
