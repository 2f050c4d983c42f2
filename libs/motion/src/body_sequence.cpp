// Arm and thigh room, intersection checks and repair over a motion, and the per-frame arrays (see body_sequence.h).
#include "layers/motion/body_sequence.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <optional>

#include "intersection_repair.h"
#include "layers/body/pose_body.h"
#include "layers/body/skinning.h"
#include "layers/core/error.h"

namespace layers::motion {
namespace {

body::FrameIntersection check_pose(const body::Body& body, const body::SelfIntersection& si, const body::Pose& pose) {
  geometry::Points v;
  body::skin(body.rest.vertices, body.weights, body.skeleton, body::forward_kinematics(body.skeleton, pose), v);
  return si.check(v);
}

// The repair's size per frame it changed: the largest turn of a limb root
// against its pose before the repair (rad) and the largest move of a skin
// vertex (m).
void measure_corrections(const body::Body& body, const std::vector<body::Pose>& before,
                         const std::vector<body::Pose>& after, IntersectionReport& report) {
  const body::Skeleton& sk = body.skeleton;
  const std::array<int, 4> roots{sk.require("LeftArm"), sk.require("RightArm"), sk.require("LeftUpLeg"),
                                 sk.require("RightUpLeg")};
  for (std::size_t f = 0; f < before.size(); ++f) {
    double turn = 0.0;
    for (int j : roots) turn = std::max(turn, before[f].local[j].angularDistance(after[f].local[j]));
    if (turn < 1e-9) continue;
    ++report.corrected;
    report.max_turn = std::max(report.max_turn, turn);
    geometry::Points a, b;
    body::skin(body.rest.vertices, body.weights, sk, body::forward_kinematics(sk, before[f]), a);
    body::skin(body.rest.vertices, body.weights, sk, body::forward_kinematics(sk, after[f]), b);
    report.max_shift = std::max(report.max_shift, static_cast<double>((a - b).rowwise().norm().maxCoeff()));
  }
}

}  // namespace

std::string RoomReport::describe(const std::string& limbs, int of) const {
  char line[160];
  std::snprintf(line, sizeof line, "%s turned in %d of %d frames, by up to %.2f rad", limbs.c_str(), frames, of, turn);
  return line;
}

BodySequence generate_body_sequence(const body::Body& body, const MotionSource& motion,
                                    const SequenceOptions& options) {
  const std::string& policy = options.on_intersection;
  if (policy != "longest_run" && policy != "first_run" && policy != "drop" && policy != "keep")
    throw InputError("body", "on_intersection", "longest_run, first_run, drop or keep", "'" + policy + "'");
  const body::Skeleton& sk = body.skeleton;
  const body::SelfIntersection si(body, options.intersection);
  const int n = motion.num_frames();

  std::vector<body::Pose> poses(n);
  std::vector<body::FrameIntersection> found(n);
  IntersectionReport report;
  report.frames = n;
  report.crossing_limbs = options.intersection.exact ? 2 : 0;
  for (int f = 0; f < n; ++f) poses[f] = motion.pose(f);
  report.arm_room = make_room(body, si, Room::arms, options.arm_room, options.max_arm_room_turn, poses);
  report.thigh_room = make_room(body, si, Room::legs, options.thigh_room, options.max_thigh_room_turn, poses);
  for (int f = 0; f < n; ++f) {
    found[f] = check_pose(body, si, poses[f]);
    report.worst_before = std::max(report.worst_before, found[f].depth);
    if (found[f].offends()) ++report.intersecting;
    report.crossing_before += found[f].crossings;
  }

  const auto needs_repair = [&](const std::vector<body::FrameIntersection>& r) {
    return std::any_of(r.begin(), r.end(), [](const body::FrameIntersection& x) { return x.needs_repair(); });
  };
  if (options.resolve && needs_repair(found)) {
    std::vector<char> was_bad(n);
    for (int f = 0; f < n; ++f) was_bad[f] = found[f].offends();
    const std::vector<body::Pose> original = poses;
    const std::vector<body::FrameIntersection> before = found;
    const auto deep = [&](const std::vector<body::FrameIntersection>& r) {
      return std::count_if(r.begin(), r.end(), [](const body::FrameIntersection& x) { return x.offends(); });
    };
    RepairLimits limits{options.max_arm_correction, options.max_leg_correction, {}};
    // The arms' crossings only: clearing the thighs' (a spin's, a squat's)
    // takes the legs' whole 0.35 rad, moves the feet apart by a quarter of a
    // metre and presses skirts and dresses into the body (measured on
    // small's scenes).
    limits.crossings = {options.intersection.exact, options.intersection.exact, false, false};
    repair_intersections(body, si, limits, poses, found);
    // Aiming at the crossings moves more, and the spread of a large turn
    // can push a neighbouring frame's arm into the body. Frames the depth
    // alone would clear are never lost to that: the arms left deep stop
    // aiming at their crossings, then both do, and the repair with the
    // fewest deep frames is kept.
    for (int attempt = 0; attempt < 2 && options.intersection.exact && deep(found) > 0; ++attempt) {
      RepairLimits fewer = limits;
      for (int limb = 0; limb < 4; ++limb) {
        bool drop = attempt == 1;
        for (int f = 0; f < n && !drop; ++f) drop = found[f].limb_shortfall[limb] > 0.0;
        if (drop) fewer.crossings[limb] = false;
      }
      std::vector<body::Pose> p = original;
      std::vector<body::FrameIntersection> r = before;
      repair_intersections(body, si, fewer, p, r);
      if (deep(r) < deep(found)) {
        poses = std::move(p);
        found = std::move(r);
        limits = fewer;
      }
    }
    report.crossing_limbs = static_cast<int>(std::count(limits.crossings.begin(), limits.crossings.end(), true));
    for (int f = 0; f < n; ++f) found[f] = check_pose(body, si, poses[f]);
    for (int f = 0; f < n; ++f) report.resolved += was_bad[f] && !found[f].offends();
    measure_corrections(body, original, poses, report);
  }

  std::vector<char> bad(n, 0);
  for (int f = 0; f < n; ++f) {
    bad[f] = found[f].offends();
    report.remaining += bad[f];
    report.crossing_after += found[f].crossings;
    report.worst_after = std::max(report.worst_after, found[f].depth);
  }

  // Which frames are written.
  std::vector<int> keep;
  if (policy == "keep") {
    for (int f = 0; f < n; ++f) keep.push_back(f);
  } else if (policy == "drop") {
    for (int f = 0; f < n; ++f)
      if (!bad[f]) keep.push_back(f);
  } else if (policy == "first_run") {
    for (int f = 0; f < n && !bad[f]; ++f) keep.push_back(f);
  } else {
    int best_start = 0, best_len = 0;
    for (int f = 0; f < n;) {
      if (bad[f]) {
        ++f;
        continue;
      }
      int g = f;
      while (g < n && !bad[g]) ++g;
      if (g - f > best_len) {
        best_len = g - f;
        best_start = f;
      }
      f = g;
    }
    for (int f = best_start; f < best_start + best_len; ++f) keep.push_back(f);
  }
  report.dropped = n - static_cast<int>(keep.size());
  if (keep.empty())
    throw InputError("motion", motion.describe(), "at least one frame without body self-intersection",
                     "all " + std::to_string(n) + " frames intersect (deepest " +
                         std::to_string(static_cast<int>(std::round(report.worst_after * 1000))) + " mm)");

  BodySequence seq;
  seq.motion = motion.describe();
  seq.num_frames = static_cast<int>(keep.size());
  seq.num_vertices = body.num_vertices();
  seq.num_joints = sk.num_joints();
  seq.intersection = report;
  seq.source_frame = keep;
  const std::size_t nv = static_cast<std::size_t>(seq.num_vertices), nj = static_cast<std::size_t>(seq.num_joints);
  seq.positions.resize(keep.size() * nv * 3);
  seq.root.resize(keep.size() * 3);
  seq.root_rot.resize(keep.size() * 4);
  seq.joints.resize(keep.size() * nj * 12);
  std::optional<body::SkinUntangler> untangler;
  if (options.skin_untangle.passes > 0) untangler.emplace(body);
  for (std::size_t i = 0; i < keep.size(); ++i) {
    body::BodyFrame frame = body::pose_body(body, poses[keep[i]]);
    if (untangler) {
      const body::SkinUntangleResult r = untangler->apply(frame.vertices, options.skin_untangle);
      seq.intersection.skin_crossing_before += r.crossing_before;
      seq.intersection.skin_crossing_after += r.crossing_after;
      seq.intersection.skin_frames += r.moved > 0;
    }
    std::copy(frame.vertices.data(), frame.vertices.data() + nv * 3, seq.positions.data() + i * nv * 3);
    for (int k = 0; k < 3; ++k) seq.root[i * 3 + k] = static_cast<float>(frame.joints.position[0][k]);
    const body::Quat& q = frame.joints.rotation[0];
    const float wxyz[4] = {static_cast<float>(q.w()), static_cast<float>(q.x()), static_cast<float>(q.y()),
                           static_cast<float>(q.z())};
    std::copy(wxyz, wxyz + 4, seq.root_rot.data() + i * 4);
    body::joint_matrices(frame.joints, seq.joints.data() + i * nj * 12);
  }
  return seq;
}

geometry::Points frame_vertices(const BodySequence& sequence, int frame) {
  const std::ptrdiff_t size = static_cast<std::ptrdiff_t>(sequence.num_vertices) * 3;
  geometry::Points p(sequence.num_vertices, 3);
  std::copy(sequence.positions.begin() + frame * size, sequence.positions.begin() + (frame + 1) * size, p.data());
  return p;
}

}  // namespace layers::motion
