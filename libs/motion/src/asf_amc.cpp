// ASF/AMC reading (see asf_amc.h).
#include "layers/motion/asf_amc.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <vector>

#include "layers/core/error.h"
#include "layers/core/text_file.h"

namespace layers::motion {
namespace {

namespace fs = std::filesystem;

struct Bone {
  std::string name;
  body::Vec3 direction = body::Vec3::Zero();
  double length = 0;
  body::Quat axis = body::Quat::Identity();  // C
  std::vector<int> dof;                      // 0..2: rx, ry, rz; 3..5: tx, ty, tz (root only)
  int parent = -1;                           // bone index; -1: the root
  int line = 0;
};

struct Skeleton {
  double length_unit = 1, angle_unit = M_PI / 180;
  Bone root;  // name "root", its order as dofs, its orientation as axis
  std::vector<Bone> bones;
  std::map<std::string, int> index;
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

// Lines split into words, '#' comments dropped, with 1-based numbers.
struct Line {
  int number = 0;
  std::vector<std::string> words;
};

std::vector<Line> lines_of(const std::string& path) {
  std::istringstream in(read_text_file(path));
  std::vector<Line> out;
  std::string text;
  int number = 0;
  while (std::getline(in, text)) {
    ++number;
    const auto hash = text.find('#');
    if (hash != std::string::npos) text.resize(hash);
    std::istringstream words(text);
    Line l{number, {}};
    for (std::string w; words >> w;) l.words.push_back(w);
    if (!l.words.empty()) out.push_back(std::move(l));
  }
  return out;
}

[[noreturn]] void fail(const std::string& path, int line, const std::string& expected, const std::string& got) {
  throw InputError(path + ":" + std::to_string(line), "", expected, got);
}

double number(const std::string& path, const Line& l, std::size_t k, const std::string& what) {
  if (k >= l.words.size()) fail(path, l.number, what, "nothing");
  const std::string& w = l.words[k];
  char* end = nullptr;
  const double v = std::strtod(w.c_str(), &end);
  if (end == w.c_str() || *end != '\0' || !std::isfinite(v) || std::fabs(v) > 1e6)
    fail(path, l.number, what, "'" + w + "'");
  return v;
}

// Rotations about x, y, z (0, 1, 2) by `angles`, applied in `order` (the
// first listed first): the product R_last * ... * R_first.
body::Quat rotation(const std::vector<int>& order, const std::vector<double>& angles) {
  body::Quat q = body::Quat::Identity();
  for (std::size_t k = 0; k < order.size(); ++k)
    q = body::Quat(Eigen::AngleAxisd(angles[k], body::Vec3::Unit(order[k]))) * q;
  return q;
}

// An axis order word ("XYZ") as axis indices.
std::vector<int> axis_order(const std::string& path, const Line& l, const std::string& word) {
  const std::string w = lower(word);
  std::vector<int> order;
  for (char c : w)
    if (c >= 'x' && c <= 'z') order.push_back(c - 'x');
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  if (w.size() != 3 || sorted != std::vector<int>{0, 1, 2})
    fail(path, l.number, "an axis order of X, Y and Z (e.g. XYZ)", "'" + word + "'");
  return order;
}

// A dof or root order word: rx ry rz tx ty tz (0-5); "l" (bone length) is
// not a motion the body can follow.
int dof_of(const std::string& path, const Line& l, const std::string& word) {
  static const std::map<std::string, int> dofs = {{"rx", 0}, {"ry", 1}, {"rz", 2}, {"tx", 3}, {"ty", 4}, {"tz", 5}};
  const auto it = dofs.find(lower(word));
  if (it == dofs.end())
    fail(path, l.number, "degrees of freedom among rx, ry, rz (tx, ty, tz: root)", "'" + word + "'");
  return it->second;
}

Skeleton read_asf(const std::string& path) {
  const std::vector<Line> lines = lines_of(path);
  Skeleton s;
  std::string section;
  bool root_seen = false, hierarchy = false;
  Bone* bone = nullptr;
  std::vector<double> orientation{0, 0, 0};
  std::vector<int> root_axis{0, 1, 2};
  for (const Line& l : lines) {
    const std::string key = lower(l.words[0]);
    if (key[0] == ':') {
      section = key;
      if (section == ":root") root_seen = true;
      if (section == ":units" || section == ":root" || section == ":bonedata" || section == ":hierarchy") continue;
      continue;  // :version, :name, :documentation: nothing the motion needs
    }
    if (section == ":units") {
      if (key == "length") s.length_unit = number(path, l, 1, "a length unit");
      if (key == "angle") {
        const std::string unit = l.words.size() > 1 ? lower(l.words[1]) : "";
        if (unit != "deg" && unit != "rad") fail(path, l.number, "angle deg or rad", "'" + unit + "'");
        s.angle_unit = unit == "deg" ? M_PI / 180 : 1.0;
      }
    } else if (section == ":root") {
      if (key == "order") {
        for (std::size_t k = 1; k < l.words.size(); ++k) s.root.dof.push_back(dof_of(path, l, l.words[k]));
      } else if (key == "axis") {
        root_axis = axis_order(path, l, l.words.size() > 1 ? l.words[1] : "");
      } else if (key == "orientation") {
        for (int k = 0; k < 3; ++k) orientation[k] = number(path, l, 1 + k, "three orientation angles");
      }
    } else if (section == ":bonedata") {
      if (key == "begin") {
        s.bones.emplace_back();
        bone = &s.bones.back();
        bone->line = l.number;
      } else if (key == "end") {
        if (!bone || bone->name.empty()) fail(path, l.number, "a bone with a name before 'end'", "none");
        if (s.index.count(bone->name) || bone->name == "root")
          fail(path, l.number, "distinct bone names", "'" + bone->name + "' twice");
        s.index[bone->name] = static_cast<int>(s.bones.size()) - 1;
        bone = nullptr;
      } else if (!bone) {
        fail(path, l.number, "'begin' before a bone's data", "'" + l.words[0] + "'");
      } else if (key == "name") {
        bone->name = l.words.size() > 1 ? l.words[1] : "";
      } else if (key == "direction") {
        for (int k = 0; k < 3; ++k) bone->direction[k] = number(path, l, 1 + k, "a direction x y z");
        if (!(bone->direction.norm() > 0)) fail(path, l.number, "a non-zero direction", "0 0 0");
        bone->direction.normalize();
      } else if (key == "length") {
        bone->length = number(path, l, 1, "a length");
        if (bone->length < 0) fail(path, l.number, "a length of 0 or more", l.words[1]);
      } else if (key == "axis") {
        std::vector<double> a(3);
        for (int k = 0; k < 3; ++k) a[k] = number(path, l, 1 + k, "three axis angles and their order");
        const std::vector<int> order = axis_order(path, l, l.words.size() > 4 ? l.words[4] : "");
        std::vector<double> ordered;
        for (int axis : order) ordered.push_back(a[axis] * s.angle_unit);
        bone->axis = rotation(order, ordered);
      } else if (key == "dof") {
        for (std::size_t k = 1; k < l.words.size(); ++k) {
          const int d = dof_of(path, l, l.words[k]);
          if (d > 2) fail(path, l.number, "rotations rx, ry, rz for a bone", "'" + l.words[k] + "'");
          bone->dof.push_back(d);
        }
      }
    } else if (section == ":hierarchy") {
      if (key == "begin") {
        hierarchy = true;
        continue;
      }
      if (key == "end") continue;
      const std::string parent = l.words[0];
      const int p = parent == "root" ? -1 : s.index.count(parent) ? s.index.at(parent) : -2;
      if (p == -2) fail(path, l.number, "a bone of :bonedata (or root) as parent", "'" + parent + "'");
      for (std::size_t k = 1; k < l.words.size(); ++k) {
        const auto it = s.index.find(l.words[k]);
        if (it == s.index.end()) fail(path, l.number, "bones of :bonedata as children", "'" + l.words[k] + "'");
        if (s.bones[static_cast<std::size_t>(it->second)].parent != -1 || it->second == p)
          fail(path, l.number, "each bone under one parent", "'" + l.words[k] + "' again");
        s.bones[static_cast<std::size_t>(it->second)].parent = p;
      }
    }
  }
  if (!root_seen || s.root.dof.empty()) fail(path, 1, "a :root section with its order", "none");
  if (!hierarchy || s.bones.empty()) fail(path, 1, "a :bonedata and a :hierarchy section", "none");
  if (!(s.length_unit > 0)) fail(path, 1, "a positive :units length", std::to_string(s.length_unit));
  if (static_cast<int>(s.bones.size()) + 1 > kMaxBvhJoints)
    fail(path, 1, "at most " + std::to_string(kMaxBvhJoints) + " joints", std::to_string(s.bones.size() + 1));
  std::vector<double> root_angles;
  for (int axis : root_axis) root_angles.push_back(orientation[axis] * s.angle_unit);
  s.root.name = "root";
  s.root.axis = rotation(root_axis, root_angles);
  return s;
}

// Bones in an order where parents come first (the hierarchy's, from the
// root down); a bone no chain reaches from the root is refused.
std::vector<int> parents_first(const Skeleton& s, const std::string& path) {
  std::vector<int> order;
  std::vector<char> placed(s.bones.size(), 0);
  std::vector<int> frontier{-1};
  while (!frontier.empty()) {
    const int p = frontier.front();
    frontier.erase(frontier.begin());
    for (std::size_t b = 0; b < s.bones.size(); ++b)
      if (!placed[b] && s.bones[b].parent == p && (p == -1 ? true : placed[static_cast<std::size_t>(p)])) {
        placed[b] = 1;
        order.push_back(static_cast<int>(b));
        frontier.push_back(static_cast<int>(b));
      }
  }
  for (std::size_t b = 0; b < s.bones.size(); ++b)
    if (!placed[b])
      fail(path, s.bones[b].line, "every bone in the :hierarchy under root", "'" + s.bones[b].name + "' in none");
  return order;
}

}  // namespace

std::string asf_for_amc(const std::string& amc_path) {
  const fs::path amc(amc_path);
  const fs::path folder = amc.parent_path().empty() ? fs::path(".") : amc.parent_path();
  const std::string stem = amc.stem().string();
  const auto underscore = stem.find('_');
  if (underscore != std::string::npos) {
    const fs::path subject = folder / (stem.substr(0, underscore) + ".asf");
    if (fs::is_regular_file(subject)) return subject.string();
  }
  std::vector<std::string> found;
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(folder, ec))
    if (e.is_regular_file() && lower(e.path().extension().string()) == ".asf") found.push_back(e.path().string());
  if (found.size() != 1)
    throw InputError(amc_path, "skeleton",
                     "its skeleton beside it (<subject>.asf for <subject>_<trial>.amc, or the folder's only .asf)",
                     found.empty() ? "no .asf file" : std::to_string(found.size()) + " .asf files");
  return found.front();
}

BvhClip read_asf_amc(const std::string& amc_path, const std::string& asf_path, double fps) {
  const std::string asf = asf_path.empty() ? asf_for_amc(amc_path) : asf_path;
  if (!(fps > 0) || 1.0 / fps <= kMinBvhFrameTime || 1.0 / fps > kMaxBvhFrameTime)
    throw InputError(amc_path, "fps", "a frame rate from 1 to 10000", std::to_string(fps));
  const Skeleton s = read_asf(asf);
  const std::vector<int> order = parents_first(s, asf);
  const double metres = 0.0254 / s.length_unit;

  // Joint 0 the root, then the bones parents first.
  BvhClip clip;
  clip.source = amc_path;
  clip.frame_time = 1.0 / fps;
  std::vector<int> joint_of(s.bones.size(), -1);
  BvhJoint root;
  root.name = "root";
  for (int d : s.root.dof)
    root.channels.push_back(d == 0   ? BvhChannel::Xrotation
                            : d == 1 ? BvhChannel::Yrotation
                            : d == 2 ? BvhChannel::Zrotation
                            : d == 3 ? BvhChannel::Xposition
                            : d == 4 ? BvhChannel::Yposition
                                     : BvhChannel::Zposition);
  clip.joints.push_back(root);
  int column = static_cast<int>(root.channels.size());
  for (int b : order) {
    const Bone& bone = s.bones[static_cast<std::size_t>(b)];
    BvhJoint j;
    j.name = bone.name;
    j.parent = bone.parent < 0 ? 0 : joint_of[static_cast<std::size_t>(bone.parent)];
    if (bone.parent >= 0) {
      const Bone& p = s.bones[static_cast<std::size_t>(bone.parent)];
      j.offset = p.direction * p.length * metres;  // the parent bone's end
    }
    for (int d : bone.dof)
      j.channels.push_back(d == 0 ? BvhChannel::Xrotation : d == 1 ? BvhChannel::Yrotation : BvhChannel::Zrotation);
    j.first_channel = column;
    column += static_cast<int>(j.channels.size());
    joint_of[static_cast<std::size_t>(b)] = static_cast<int>(clip.joints.size());
    clip.joints.push_back(j);
  }
  for (std::size_t b = 0; b < s.bones.size(); ++b) {
    bool leaf = true;
    for (const Bone& o : s.bones) leaf = leaf && o.parent != static_cast<int>(b);
    if (!leaf) continue;
    BvhJoint& j = clip.joints[static_cast<std::size_t>(joint_of[b])];
    j.has_end_site = true;
    j.end_site = s.bones[b].direction * s.bones[b].length * metres;
  }

  // The motion.
  const std::vector<Line> lines = lines_of(amc_path);
  std::vector<std::vector<double>> values;  // current frame: per joint, its values
  std::vector<char> seen;
  int frame_line = 0;
  const auto finish = [&]() {
    if (values.empty()) return;
    for (std::size_t j = 0; j < clip.joints.size(); ++j)
      if (!seen[j] && !clip.joints[j].channels.empty())
        fail(amc_path, frame_line, "a line for every moving bone in each frame",
             "none for '" + clip.joints[j].name + "'");
    std::vector<body::Quat> rot(clip.joints.size(), body::Quat::Identity());
    std::vector<body::Vec3> trans(clip.joints.size(), body::Vec3::Zero());
    for (std::size_t j = 0; j < clip.joints.size(); ++j) {
      const Bone& bone = j == 0 ? s.root : s.bones[static_cast<std::size_t>(order[j - 1])];
      std::vector<int> axes;
      std::vector<double> angles;
      body::Vec3 t = clip.joints[j].offset;
      for (std::size_t k = 0; k < bone.dof.size(); ++k) {
        const int d = bone.dof[k];
        if (d < 3) {
          axes.push_back(d);
          angles.push_back(values[j][k] * s.angle_unit);
        } else {
          t[d - 3] = values[j][k] * metres;
        }
      }
      rot[j] = (bone.axis * rotation(axes, angles) * bone.axis.conjugate()).normalized();
      trans[j] = t;
    }
    clip.rotation.push_back(std::move(rot));
    clip.translation.push_back(std::move(trans));
    if (static_cast<long>(clip.rotation.size()) > kMaxBvhFrames ||
        static_cast<long>(clip.rotation.size()) * static_cast<long>(clip.joints.size()) > kMaxBvhJointFrames ||
        static_cast<double>(clip.rotation.size()) / fps > kMaxBvhSeconds)
      fail(amc_path, frame_line, "a clip within the BVH bounds (frames, joints x frames, 3600 s)", "more frames");
  };
  std::map<std::string, int> joint_index;
  for (std::size_t j = 0; j < clip.joints.size(); ++j) joint_index[clip.joints[j].name] = static_cast<int>(j);
  for (const Line& l : lines) {
    const std::string& w = l.words[0];
    if (w[0] == ':') continue;  // :FULLY-SPECIFIED, :DEGREES
    if (l.words.size() == 1 && std::all_of(w.begin(), w.end(), [](char c) { return std::isdigit(c); })) {
      finish();
      values.assign(clip.joints.size(), {});
      seen.assign(clip.joints.size(), 0);
      frame_line = l.number;
      continue;
    }
    if (values.empty()) fail(amc_path, l.number, "a frame number before the first bone line", "'" + w + "'");
    const auto it = joint_index.find(w);
    if (it == joint_index.end()) fail(amc_path, l.number, "a bone of " + asf, "'" + w + "'");
    const std::size_t j = static_cast<std::size_t>(it->second);
    const Bone& bone = j == 0 ? s.root : s.bones[static_cast<std::size_t>(order[j - 1])];
    if (l.words.size() - 1 != bone.dof.size())
      fail(amc_path, l.number, std::to_string(bone.dof.size()) + " values for '" + w + "' (its dof in " + asf + ")",
           std::to_string(l.words.size() - 1));
    if (seen[j]) fail(amc_path, l.number, "one line per bone in a frame", "'" + w + "' twice");
    seen[j] = 1;
    for (std::size_t k = 1; k < l.words.size(); ++k) values[j].push_back(number(amc_path, l, k, "a number"));
  }
  finish();
  if (clip.rotation.empty())
    throw InputError(amc_path, "", "frames of motion (a frame number, then bone lines)", "none");
  return clip;
}

bool is_clip_file(const std::string& path) {
  const std::string ext = lower(fs::path(path).extension().string());
  return ext == ".bvh" || ext == ".amc";
}

BvhClip read_clip(const std::string& path) {
  return lower(fs::path(path).extension().string()) == ".amc" ? read_asf_amc(path) : read_bvh(path);
}

}  // namespace layers::motion
