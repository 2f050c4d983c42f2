// Writing a clip as BVH (see bvh_write.h).
#include "layers/motion/bvh_write.h"

#include <cmath>
#include <cstdio>
#include <functional>
#include <sstream>
#include <vector>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"

namespace layers::motion {
namespace {

constexpr double kCentimetres = 100.0;

std::string fixed(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.6f", v);
  return buf;
}

std::vector<std::vector<int>> children_of(const BvhClip& clip) {
  std::vector<std::vector<int>> children(clip.joints.size());
  for (std::size_t j = 1; j < clip.joints.size(); ++j)
    children[static_cast<std::size_t>(clip.joints[j].parent)].push_back(static_cast<int>(j));
  return children;
}

}  // namespace

BvhClip without_joints(const BvhClip& clip, const std::set<std::string>& drop) {
  std::vector<int> keep_index(clip.joints.size(), -1);
  BvhClip out;
  out.source = clip.source;
  out.frame_time = clip.frame_time;
  for (std::size_t j = 0; j < clip.joints.size(); ++j) {
    const BvhJoint& joint = clip.joints[j];
    const bool dropped =
        drop.count(joint.name) || (joint.parent >= 0 && keep_index[static_cast<std::size_t>(joint.parent)] < 0);
    if (dropped) {
      // The kept parent of a dropped joint ends where that joint starts.
      if (joint.parent >= 0 && keep_index[static_cast<std::size_t>(joint.parent)] >= 0) {
        BvhJoint& parent = out.joints[static_cast<std::size_t>(keep_index[static_cast<std::size_t>(joint.parent)])];
        if (!parent.has_end_site) {
          parent.has_end_site = true;
          parent.end_site = joint.offset;
        }
      }
      continue;
    }
    BvhJoint copy = joint;
    copy.parent = joint.parent < 0 ? -1 : keep_index[static_cast<std::size_t>(joint.parent)];
    keep_index[j] = static_cast<int>(out.joints.size());
    out.joints.push_back(copy);
  }
  // A kept joint with kept children has no End Site.
  for (const BvhJoint& j : out.joints)
    if (j.parent >= 0) out.joints[static_cast<std::size_t>(j.parent)].has_end_site = false;
  for (std::size_t f = 0; f < clip.rotation.size(); ++f) {
    std::vector<body::Quat> r;
    std::vector<body::Vec3> t;
    for (std::size_t j = 0; j < clip.joints.size(); ++j)
      if (keep_index[j] >= 0) {
        r.push_back(clip.rotation[f][j]);
        t.push_back(clip.translation[f][j]);
      }
    out.rotation.push_back(std::move(r));
    out.translation.push_back(std::move(t));
  }
  return out;
}

void write_bvh(const BvhClip& clip, const std::string& path) {
  if (clip.joints.empty() || clip.joints[0].parent != -1) throw Error("write_bvh: a clip without a root joint first");
  for (std::size_t f = 0; f < clip.translation.size(); ++f)
    for (std::size_t j = 1; j < clip.joints.size(); ++j)
      if ((clip.translation[f][j] - clip.joints[j].offset).norm() > 1e-9)
        throw InputError(clip.source, "joint '" + clip.joints[j].name + "'",
                         "joints other than the root at their offsets (BVH here has no other position channels)",
                         "a translation off it in frame " + std::to_string(f));
  const auto children = children_of(clip);
  std::ostringstream out;
  std::vector<int> order;  // depth first: the order of the channels
  const std::function<void(int, int)> joint = [&](int j, int depth) {
    const std::string pad(static_cast<std::size_t>(depth) * 2, ' ');
    const BvhJoint& b = clip.joints[static_cast<std::size_t>(j)];
    order.push_back(j);
    out << pad << (j == 0 ? "ROOT " : "JOINT ") << b.name << "\n" << pad << "{\n";
    out << pad << "  OFFSET " << fixed(b.offset.x() * kCentimetres) << ' ' << fixed(b.offset.y() * kCentimetres) << ' '
        << fixed(b.offset.z() * kCentimetres) << "\n";
    out << pad << "  CHANNELS "
        << (j == 0 ? "6 Xposition Yposition Zposition Zrotation Yrotation Xrotation"
                   : "3 Zrotation Yrotation Xrotation")
        << "\n";
    for (int c : children[static_cast<std::size_t>(j)]) joint(c, depth + 1);
    if (children[static_cast<std::size_t>(j)].empty()) {
      const body::Vec3 e = b.has_end_site ? b.end_site : body::Vec3::Zero();
      out << pad << "  End Site\n"
          << pad << "  {\n"
          << pad << "    OFFSET " << fixed(e.x() * kCentimetres) << ' ' << fixed(e.y() * kCentimetres) << ' '
          << fixed(e.z() * kCentimetres) << "\n"
          << pad << "  }\n";
    }
    out << pad << "}\n";
  };
  out << "HIERARCHY\n";
  joint(0, 0);
  char frame_time[40];
  std::snprintf(frame_time, sizeof frame_time, "%.12g", clip.frame_time);
  out << "MOTION\nFrames: " << clip.num_frames() << "\nFrame Time: " << frame_time << "\n";
  for (int f = 0; f < clip.num_frames(); ++f) {
    const body::Vec3 root = clip.translation[static_cast<std::size_t>(f)][0] * kCentimetres;
    out << fixed(root.x()) << ' ' << fixed(root.y()) << ' ' << fixed(root.z());
    for (int j : order) {
      // R = Rz(a) * Ry(b) * Rx(c).
      const body::Vec3 zyx =
          clip.rotation[static_cast<std::size_t>(f)][static_cast<std::size_t>(j)].toRotationMatrix().eulerAngles(2, 1,
                                                                                                                 0) *
          (180.0 / M_PI);
      out << ' ' << fixed(zyx[0]) << ' ' << fixed(zyx[1]) << ' ' << fixed(zyx[2]);
    }
    out << "\n";
  }
  write_text_atomic(path, out.str());
}

}  // namespace layers::motion
