// BVH reading, resampling and forward kinematics (see bvh.h).
#include "layers/motion/bvh.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <istream>
#include <sstream>

#include "layers/core/error.h"

namespace layers::motion {
namespace {

// Channel and offset values beyond this (degrees, or the clip's length
// unit) are damage, not motion: they would overflow the pose maths.
constexpr double kMaxBvhValue = 1e6;

// A number as written by %g (1e+30, 0.008333), for messages.
std::string shortest(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Whitespace-separated tokens with their line numbers, read lazily so that
// the MOTION data can be taken line by line afterwards.
class Tokens {
 public:
  Tokens(std::istream& in, const std::string& name) : in_(in), name_(name) {}

  // Next token, or "" at end of file.
  std::string next() {
    while (pos_ >= words_.size()) {
      if (!std::getline(in_, text_)) return "";
      ++line_;
      split();
    }
    return words_[pos_++];
  }
  std::string expect_any(const std::string& what) {
    std::string t = next();
    if (t.empty()) fail(what, "end of file");
    return t;
  }
  void expect(const std::string& word) {
    std::string t = next();
    if (t != word) fail("'" + word + "'", t.empty() ? "end of file" : "'" + t + "'");
  }
  double number(const std::string& what) {
    std::string t = expect_any(what);
    char* end = nullptr;
    double v = std::strtod(t.c_str(), &end);
    if (end == t.c_str() || *end != '\0' || !std::isfinite(v)) fail(what, "'" + t + "'");
    return v;
  }
  // The rest of the current line (after the tokens already taken).
  std::string rest_of_line() {
    std::string out;
    for (; pos_ < words_.size(); ++pos_) out += (out.empty() ? "" : " ") + words_[pos_];
    return out;
  }
  bool next_line(std::string& out) {
    if (!std::getline(in_, out)) return false;
    ++line_;
    return true;
  }
  int line() const { return line_; }
  [[noreturn]] void fail(const std::string& expected, const std::string& got) const {
    throw InputError(name_, "line " + std::to_string(line_), expected, got);
  }

 private:
  void split() {
    words_.clear();
    pos_ = 0;
    std::istringstream ss(text_);
    std::string w;
    while (ss >> w) words_.push_back(w);
  }
  std::istream& in_;
  const std::string& name_;
  std::string text_;
  std::vector<std::string> words_;
  std::size_t pos_ = 0;
  int line_ = 0;
};

bool parse_channel(const std::string& s, BvhChannel& c) {
  static const char* names[] = {"Xposition", "Yposition", "Zposition", "Xrotation", "Yrotation", "Zrotation"};
  for (int i = 0; i < 6; ++i)
    if (s == names[i]) {
      c = static_cast<BvhChannel>(i);
      return true;
    }
  return false;
}

body::Vec3 read_offset(Tokens& t) {
  t.expect("OFFSET");
  body::Vec3 v;
  for (int k = 0; k < 3; ++k) {
    v[k] = t.number("three OFFSET numbers");
    if (std::fabs(v[k]) > kMaxBvhValue) t.fail("OFFSET values within +-1e+06", shortest(v[k]));
  }
  return v;
}

// Parses "{ OFFSET ... CHANNELS ... (JOINT ...| End Site ...)* }" for a
// joint whose name has been read.
void parse_joint(Tokens& t, BvhClip& clip, const std::string& name, int parent, int& channels, int depth) {
  if (depth > 256) t.fail("a hierarchy at most 256 deep", "a deeper one");
  BvhJoint joint;
  joint.name = name;
  joint.parent = parent;
  t.expect("{");
  joint.offset = read_offset(t);
  t.expect("CHANNELS");
  double count = t.number("a channel count");
  if (count < 0 || count > 6 || count != std::floor(count))
    t.fail("a channel count from 0 to 6", std::to_string(count));
  const std::string names = t.rest_of_line();
  std::istringstream ss(names);
  std::string word;
  while (ss >> word) {
    BvhChannel c;
    if (!parse_channel(word, c)) t.fail("a channel name (Xposition ... Zrotation)", "'" + word + "'");
    joint.channels.push_back(c);
  }
  if (static_cast<int>(joint.channels.size()) != static_cast<int>(count))
    t.fail(std::to_string(static_cast<int>(count)) + " channel names after 'CHANNELS " +
               std::to_string(static_cast<int>(count)) + "' for joint " + name,
           std::to_string(joint.channels.size()));
  joint.first_channel = channels;
  channels += static_cast<int>(count);
  const int index = static_cast<int>(clip.joints.size());
  if (index >= kMaxBvhJoints)
    t.fail("at most " + std::to_string(kMaxBvhJoints) + " joints",
           "joint " + std::to_string(index + 1) + " (" + name + ")");
  clip.joints.push_back(joint);
  while (true) {
    std::string word2 = t.expect_any("JOINT, End Site or '}'");
    if (word2 == "}") break;
    if (word2 == "JOINT") {
      parse_joint(t, clip, t.expect_any("a joint name"), index, channels, depth + 1);
    } else if (word2 == "End") {
      t.expect("Site");
      t.expect("{");
      clip.joints[index].has_end_site = true;
      clip.joints[index].end_site = read_offset(t);
      t.expect("}");
    } else {
      t.fail("JOINT, End Site or '}'", "'" + word2 + "'");
    }
  }
}

body::Vec3 apply_channels(const BvhJoint& joint, const double* values, body::Quat& rotation) {
  body::Vec3 translation = joint.offset;
  rotation = body::Quat::Identity();
  const double deg = M_PI / 180.0;
  for (std::size_t c = 0; c < joint.channels.size(); ++c) {
    const double v = values[joint.first_channel + static_cast<int>(c)];
    switch (joint.channels[c]) {
      case BvhChannel::Xposition:
        translation.x() += v;
        break;
      case BvhChannel::Yposition:
        translation.y() += v;
        break;
      case BvhChannel::Zposition:
        translation.z() += v;
        break;
      case BvhChannel::Xrotation:
        rotation = rotation * body::rot_x(v * deg);
        break;
      case BvhChannel::Yrotation:
        rotation = rotation * body::rot_y(v * deg);
        break;
      case BvhChannel::Zrotation:
        rotation = rotation * body::rot_z(v * deg);
        break;
    }
  }
  rotation.normalize();
  return translation;
}

}  // namespace

int BvhClip::index(const std::string& name) const {
  for (int j = 0; j < num_joints(); ++j)
    if (joints[j].name == name) return j;
  return -1;
}

BvhClip parse_bvh(std::istream& in, const std::string& name) {
  BvhClip clip;
  clip.source = name;
  Tokens t(in, name);
  t.expect("HIERARCHY");
  t.expect("ROOT");
  int channels = 0;
  parse_joint(t, clip, t.expect_any("a root joint name"), -1, channels, 0);

  std::string word = t.next();
  if (word == "ROOT") t.fail("MOTION (files with several roots are not supported)", "a second ROOT");
  if (word != "MOTION") t.fail("MOTION", word.empty() ? "end of file" : "'" + word + "'");
  t.expect("Frames:");
  const double frames = t.number("a frame count");
  if (!(frames >= 0 && frames <= kMaxBvhFrames) || frames != std::floor(frames))
    t.fail("a whole frame count from 0 to " + std::to_string(kMaxBvhFrames), shortest(frames));
  t.expect("Frame");
  t.expect("Time:");
  clip.frame_time = t.number("a frame time in seconds");
  if (!(clip.frame_time > kMinBvhFrameTime && clip.frame_time <= kMaxBvhFrameTime))
    t.fail("a frame time in (" + shortest(kMinBvhFrameTime) + ", " + shortest(kMaxBvhFrameTime) + "] seconds",
           shortest(clip.frame_time));
  std::string leftover = t.rest_of_line();
  if (!leftover.empty()) t.fail("the end of the Frame Time line", "'" + leftover + "'");
  // Bounds on what the frames will take, before any is read: joints x
  // frames, and the clip's length (what resampling makes of it).
  const double joint_frames = frames * static_cast<double>(clip.joints.size());
  if (joint_frames > kMaxBvhJointFrames)
    t.fail("at most " + std::to_string(kMaxBvhJointFrames) + " joints x frames",
           std::to_string(clip.joints.size()) + " joints x " + shortest(frames) + " frames");
  if (frames * clip.frame_time > kMaxBvhSeconds)
    t.fail("a clip of at most " + shortest(kMaxBvhSeconds) + " s (Frames x Frame Time)",
           shortest(frames * clip.frame_time) + " s");

  const int n = static_cast<int>(frames);
  std::vector<double> values(static_cast<std::size_t>(channels));
  std::string line;
  int read = 0;
  while (t.next_line(line)) {
    const char* p = line.c_str();
    while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
    if (*p == '\0') continue;  // blank lines are allowed
    if (read == n)
      t.fail("no more data after " + std::to_string(n) + " frames (Frames: " + std::to_string(n) + ")",
             "another frame line");
    int count = 0;
    while (true) {
      while (*p == ' ' || *p == '\t' || *p == '\r') ++p;
      if (*p == '\0') break;
      const char* start = p;
      while (*p != '\0' && *p != ' ' && *p != '\t' && *p != '\r') ++p;
      std::string token(start, p);
      char* end = nullptr;
      double v = std::strtod(token.c_str(), &end);
      if (end == token.c_str() || *end != '\0' || !std::isfinite(v) || std::fabs(v) > kMaxBvhValue)
        t.fail("a number within +-1e+06 (value " + std::to_string(count + 1) + " of frame " + std::to_string(read + 1) +
                   ")",
               "'" + token + "'");
      if (count < channels) values[count] = v;
      ++count;
    }
    if (count != channels)
      t.fail(std::to_string(channels) + " values per frame (the channels of the hierarchy)", std::to_string(count));
    std::vector<body::Quat> rot(clip.joints.size());
    std::vector<body::Vec3> trans(clip.joints.size());
    for (std::size_t j = 0; j < clip.joints.size(); ++j)
      trans[j] = apply_channels(clip.joints[j], values.data(), rot[j]);
    clip.rotation.push_back(std::move(rot));
    clip.translation.push_back(std::move(trans));
    ++read;
  }
  if (read != n)
    t.fail(std::to_string(n) + " frames (Frames: " + std::to_string(n) + ")",
           std::to_string(read) + " frames before the end of file");
  return clip;
}

BvhClip read_bvh(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, "", "a BVH file", "a directory");
  std::ifstream in(path);
  if (!in) throw InputError::message(path, "", "cannot open BVH file");
  return parse_bvh(in, path);
}

BvhClip resample(const BvhClip& clip, double fps) {
  if (!(fps > 0)) throw Error("resample: fps must be positive");
  BvhClip out;
  out.source = clip.source;
  out.joints = clip.joints;
  out.frame_time = 1.0 / fps;
  if (clip.num_frames() == 0) return out;
  const double duration = (clip.num_frames() - 1) * clip.frame_time;
  const double frames = std::floor(duration * fps + 1e-6) + 1;
  if (frames * static_cast<double>(clip.joints.size()) > kMaxBvhJointFrames)
    throw InputError(clip.source, "frames",
                     "at most " + std::to_string(kMaxBvhJointFrames) + " joints x frames at " + shortest(fps) + " fps",
                     std::to_string(clip.joints.size()) + " joints x " + shortest(frames) + " frames");
  const int m = static_cast<int>(frames);
  for (int i = 0; i < m; ++i) {
    const double s = std::min(i / fps / clip.frame_time, static_cast<double>(clip.num_frames() - 1));
    const int a = static_cast<int>(std::floor(s));
    const int b = std::min(a + 1, clip.num_frames() - 1);
    const double w = s - a;
    std::vector<body::Quat> rot(clip.joints.size());
    std::vector<body::Vec3> trans(clip.joints.size());
    for (std::size_t j = 0; j < clip.joints.size(); ++j) {
      rot[j] = body::slerp(clip.rotation[a][j], clip.rotation[b][j], w);
      trans[j] = (1.0 - w) * clip.translation[a][j] + w * clip.translation[b][j];
    }
    out.rotation.push_back(std::move(rot));
    out.translation.push_back(std::move(trans));
  }
  return out;
}

BvhWorld bvh_world(const BvhClip& clip, int frame) {
  BvhWorld w;
  const int n = clip.num_joints();
  w.rotation.resize(n);
  w.position.resize(n);
  for (int j = 0; j < n; ++j) {
    const body::Quat r = frame < 0 ? body::Quat::Identity() : clip.rotation[frame][j];
    const body::Vec3 t = frame < 0 ? clip.joints[j].offset : clip.translation[frame][j];
    const int p = clip.joints[j].parent;
    if (p < 0) {
      w.rotation[j] = r;
      w.position[j] = t;
    } else {
      w.rotation[j] = (w.rotation[p] * r).normalized();
      w.position[j] = w.position[p] + w.rotation[p] * t;
    }
  }
  return w;
}

}  // namespace layers::motion
