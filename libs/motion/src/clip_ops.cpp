// Mirrored clips and clip windows (see clip_ops.h).
#include "layers/motion/clip_ops.h"

#include <algorithm>
#include <cctype>
#include <cmath>

#include "layers/core/error.h"
#include "layers/motion/asf_amc.h"
#include "layers/motion/bvh.h"
#include "layers/motion/motion.h"

namespace layers::motion {

PoseMirror::PoseMirror(const body::Skeleton& skeleton) {
  const int n = skeleton.num_joints();
  partner_.resize(static_cast<std::size_t>(n));
  for (int j = 0; j < n; ++j) {
    const std::string& name = skeleton.names[static_cast<std::size_t>(j)];
    int other = j;
    if (name.rfind("Left", 0) == 0) {
      other = skeleton.index("Right" + name.substr(4));
    } else if (name.rfind("Right", 0) == 0) {
      other = skeleton.index("Left" + name.substr(5));
    } else if (name.size() > 1 && (name[0] == 'L' || name[0] == 'R') && std::isupper(name[1])) {
      other = skeleton.index((name[0] == 'L' ? "R" : "L") + name.substr(1));  // LHipJoint, RThumb
    }
    partner_[static_cast<std::size_t>(j)] = other >= 0 ? other : j;
  }
}

body::Pose PoseMirror::operator()(const body::Pose& pose) const {
  body::Pose out;
  out.local.resize(pose.local.size());
  for (std::size_t j = 0; j < pose.local.size(); ++j) {
    const body::Quat& q = pose.local[static_cast<std::size_t>(partner_.at(j))];
    out.local[j] = body::Quat(q.w(), q.x(), -q.y(), -q.z());
  }
  out.root = body::Vec3(-pose.root.x(), pose.root.y(), pose.root.z());
  return out;
}

std::vector<body::Pose> clip_window(const std::vector<body::Pose>& poses, int start, int frames, int ease) {
  const int n = static_cast<int>(poses.size());
  if (start < 0 || frames < 1 || start + frames > n)
    throw Error("clip window [" + std::to_string(start) + ", " + std::to_string(start + frames) +
                ") outside a clip of " + std::to_string(n) + " frames");
  ease = start > 0 ? std::clamp(ease, 0, frames / 2) : 0;
  std::vector<body::Pose> out;
  out.reserve(static_cast<std::size_t>(frames));
  for (int i = 0; i < frames; ++i) {
    double t = start + i;
    if (i < ease) {
      const double x = static_cast<double>(i) / ease;
      t = start + ease * (x * x - x * x * x / 3.0);
    } else if (ease > 0) {
      t = start + 2.0 * ease / 3.0 + (i - ease);
    }
    const int a = std::min(static_cast<int>(std::floor(t)), n - 1), b = std::min(a + 1, n - 1);
    out.push_back(body::blend(poses[static_cast<std::size_t>(a)], poses[static_cast<std::size_t>(b)], t - a));
  }
  const body::Vec3 first = out.front().root;
  for (body::Pose& p : out) {
    p.root.x() -= first.x();
    p.root.z() -= first.z();
  }
  return out;
}

int bvh_clip_frames(const std::string& path, const std::string& asset_root) {
  return resample(read_clip(find_bvh_file(path, asset_root)), kFramesPerSecond).num_frames();
}

}  // namespace layers::motion
