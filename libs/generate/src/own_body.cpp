// A user's own body as a scene's body and motion (see own_body.h).
#include "layers/generate/own_body.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>

#include "layers/body/pose_body.h"
#include "layers/core/checksum.h"
#include "layers/core/error.h"
#include "layers/import/body_import.h"
#include "layers/import/garment_file.h"
#include "layers/motion/asf_amc.h"
#include "layers/motion/body_sequence.h"
#include "layers/motion/motion.h"
#include "layers/motion/retarget.h"

namespace layers::generate {
namespace {

namespace fs = std::filesystem;

body::Body to_body(const import::ImportedBody& in) {
  body::Body b;
  b.file = in.file;
  b.rest = in.rest;
  body::Skeleton& sk = b.skeleton;
  sk.names = in.joint_names;
  sk.parents = in.parents;
  sk.rest_head = in.joint_rest;
  const int n = static_cast<int>(sk.names.size());
  // Bone tails (a bone's direction and length, which BVH retargeting aims
  // along): the head of the child that continues the bone -- the one most
  // in line with the parent bone (the neck after the chest, the fingers
  // after the hand), for the root the one carrying the most joints below
  // it (the spine) -- or for a leaf a third of its parent bone further on
  // (10 cm up for a lone root). A file has no tails: a leaf's direction
  // is a guess (docs/own-data.md).
  std::vector<int> below(static_cast<std::size_t>(n), 0);
  for (int j = n - 1; j > 0; --j)
    below[static_cast<std::size_t>(sk.parents[j])] += below[static_cast<std::size_t>(j)] + 1;
  for (int j = 0; j < n; ++j) {
    const int parent = sk.parents[j];
    const auto score = [&](int c) {
      const body::Vec3 d = sk.rest_head[c] - sk.rest_head[j];
      return parent < 0 ? static_cast<double>(below[static_cast<std::size_t>(c)])
                        : d.normalized().dot((sk.rest_head[j] - sk.rest_head[parent]).normalized());
    };
    int chain = -1;
    for (int c = 0; c < n; ++c)
      if (sk.parents[c] == j && (sk.rest_head[c] - sk.rest_head[j]).norm() > 1e-6 &&
          (chain < 0 || score(c) > score(chain)))
        chain = c;
    if (chain >= 0)
      sk.rest_tail.push_back(sk.rest_head[chain]);
    else if (parent >= 0)
      sk.rest_tail.push_back(sk.rest_head[j] + (sk.rest_head[j] - sk.rest_head[parent]) / 3.0);
    else
      sk.rest_tail.push_back(sk.rest_head[j] + body::Vec3(0, 0.1, 0));
    sk.bone_frame.push_back(body::Mat3::Identity());
  }
  b.weights.index = in.skin_index;
  b.weights.weight = in.skin_weight;
  b.t_pose = body::rest_pose(sk);
  b.soles = body::sole_vertices(b);
  return b;
}

// The body as read for the scenes of one config: every scene of a dataset
// (threads included) shares one import of its files, keyed by the settings
// and the content hash resolve_own_body recorded.
std::shared_ptr<const import::ImportedBody> imported(const OwnBodyConfig& own) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const import::ImportedBody>> cache;
  const std::string key =
      own.file + '\n' + own.mesh + '\n' + std::to_string(own.scale) + '\n' + own.animation + '\n' + own.hash;
  std::lock_guard<std::mutex> lock(mutex);
  auto& body = cache[key];
  if (!body)
    body =
        std::make_shared<const import::ImportedBody>(import::import_body(own.file, own.mesh, own.scale, own.animation));
  return body;
}

std::string describe_animation(const import::ImportedBody& in) {
  fs::path file = fs::path(in.file).lexically_normal();
  if (file.filename().empty()) file = file.parent_path();  // a folder written with a trailing '/'
  std::string d = std::string(kOwnAnimation) + ":" + file.filename().string();
  return in.animation.empty() ? d : d + "#" + in.animation;
}

// A mesh sequence's frames as the body sequence: the rest pose blended
// into the first frame (vertices linearly, the one joint by slerp), then
// the frames as they are.
motion::BodySequence sequence_of_vertices(const body::Body& b, const import::ImportedBody& in, int transition,
                                          int frames) {
  motion::BodySequence s;
  s.num_frames = transition + frames;
  s.num_vertices = b.num_vertices();
  s.num_joints = 1;
  s.motion = describe_animation(in);
  s.intersection.frames = s.num_frames;
  const std::size_t nv = static_cast<std::size_t>(s.num_vertices);
  for (int f = 0; f < s.num_frames; ++f) {
    geometry::Points v;
    body::JointTransforms t;
    if (f < transition) {
      const double w = body::smoothstep(static_cast<double>(f) / transition);
      v = ((1.0 - w) * b.rest.vertices.cast<double>() + w * in.vertices[0].cast<double>()).cast<float>();
      t.rotation.push_back(body::Quat::Identity().slerp(w, in.frames[0].rotation[0]));
      t.position.push_back((1.0 - w) * b.skeleton.rest_head[0] + w * in.frames[0].position[0]);
    } else {
      v = in.vertices[static_cast<std::size_t>(f - transition)];
      t.rotation.push_back(in.frames[static_cast<std::size_t>(f - transition)].rotation[0]);
      t.position.push_back(in.frames[static_cast<std::size_t>(f - transition)].position[0]);
    }
    s.positions.insert(s.positions.end(), v.data(), v.data() + nv * 3);
    for (int k = 0; k < 3; ++k) s.root.push_back(static_cast<float>(t.position[0][k]));
    const body::Quat& q = t.rotation[0];
    s.root_rot.insert(s.root_rot.end(), {static_cast<float>(q.w()), static_cast<float>(q.x()),
                                         static_cast<float>(q.y()), static_cast<float>(q.z())});
    s.joints.resize(s.joints.size() + 12);
    body::joint_matrices(t, s.joints.data() + s.joints.size() - 12);
    s.source_frame.push_back(f);
  }
  return s;
}

std::unique_ptr<motion::MotionSource> file_animation(const body::Body& b, const import::ImportedBody& in, int frames) {
  std::vector<body::Pose> poses;
  for (int f = 0; f < frames; ++f) {
    const import::BodyFrame& frame = in.frames[static_cast<std::size_t>(f)];
    body::Pose p = body::pose_from_world(b.skeleton, frame.rotation, frame.position[0]);
    if (!poses.empty())
      for (std::size_t j = 0; j < p.local.size(); ++j)
        p.local[j] = body::same_hemisphere(p.local[j], poses.back().local[j]);
    poses.push_back(std::move(p));
  }
  return std::make_unique<motion::PoseTrack>(std::move(poses), describe_animation(in));
}

}  // namespace

void check_own_body(const GeneratorConfig& config, const std::string& file) {
  if (!config.body.own) return;
  const OwnBodyConfig& own = *config.body.own;
  if (own.file.empty()) throw InputError(file, "body.own.file", "a body file or folder", "none given");
  if (!fs::exists(own.file))
    throw InputError(file, "body.own.file", "an existing file or folder", "'" + own.file + "'");
  const bool sequence = import::is_mesh_sequence(own.file);
  // Settings that would be ignored are refused.
  if (sequence && own.garment_pose != "bind")
    throw InputError(file, "body.own.garment_pose",
                     "bind for a mesh sequence (its garments' pose is its rest pose: body.own.mesh or the first frame)",
                     "'" + own.garment_pose + "'");
  if (sequence && !own.animation.empty())
    throw InputError(file, "body.own.animation", "nothing for a mesh sequence (it has one motion)",
                     "'" + own.animation + "'");
  if (!sequence && !own.mesh.empty())
    throw InputError(file, "body.own.mesh", "nothing for a rigged file (its meshes are the body)",
                     "'" + own.mesh + "'");
  if (config.body.variation)
    throw InputError(file, "body.variation", "nothing with body.own (a user's motion is played as it is)",
                     "a variation block");
  for (std::size_t i = 0; i < config.body.motions.size(); ++i) {
    const std::string& m = config.body.motions[i];
    const bool bvh = m.rfind("bvh:", 0) == 0 || motion::is_clip_file(m);
    if (m == kOwnAnimation || (bvh && !sequence)) continue;
    throw InputError(file, "body.motions[" + std::to_string(i) + "]",
                     sequence ? "animation (a mesh sequence plays its own frames)"
                              : "animation (the file's own) or a BVH clip retargeted onto the body",
                     "'" + m + "'");
  }
  for (std::size_t i = 0; i < config.garments.outfits.size(); ++i) {
    const OutfitConfig& o = config.garments.outfits[i];
    std::vector<std::string> entries = o.inner;
    if (o.outer != "none") entries.push_back(o.outer);
    for (const std::string& e : entries)
      if (!import::is_garment_file(e))
        throw InputError(file, "garments.outfits[" + std::to_string(i) + "]",
                         "garment files (file:<mesh>) with body.own: templates are fitted to our body", "'" + e + "'");
  }
}

void resolve_own_body(GeneratorConfig& config) {
  if (!config.body.own) return;
  OwnBodyConfig& own = *config.body.own;
  const import::ImportedBody body = import::import_body(own.file, own.mesh, own.scale, own.animation);
  if (body.joint_drift > 1e-4)
    spdlog::warn(
        "{}: joint '{}' moves up to {:.1f} mm off its offset from its parent (frame {}); the body follows "
        "joint rotations and the root's motion, so it is taken at its offset",
        own.file, body.drift_joint, body.joint_drift * 1000, body.drift_frame);
  if (body.skipped_meshes > 0)
    spdlog::warn("{}: {} mesh{} bound to no joint left out of the body", own.file, body.skipped_meshes,
                 body.skipped_meshes == 1 ? "" : "es");
  // The hash of what was read (whatever files it came from: a .gltf's
  // buffers, a folder's frames): mesh, rig, weights and every frame.
  std::string bytes;
  const auto add = [&](const void* p, std::size_t n) { bytes.append(static_cast<const char*>(p), n); };
  add(body.rest.vertices.data(), sizeof(float) * static_cast<std::size_t>(body.rest.vertices.size()));
  add(body.rest.faces.data(), sizeof(int) * static_cast<std::size_t>(body.rest.faces.size()));
  for (const std::string& name : body.joint_names) bytes += name + '\n';
  add(body.parents.data(), sizeof(int) * body.parents.size());
  add(body.skin_index.data(), sizeof(int) * static_cast<std::size_t>(body.skin_index.size()));
  add(body.skin_weight.data(), sizeof(float) * static_cast<std::size_t>(body.skin_weight.size()));
  for (const Eigen::Vector3d& p : body.joint_rest) add(p.data(), sizeof(double) * 3);
  for (const import::BodyFrame& f : body.frames)
    for (std::size_t j = 0; j < f.rotation.size(); ++j) {
      add(f.rotation[j].coeffs().data(), sizeof(double) * 4);
      add(f.position[j].data(), sizeof(double) * 3);
    }
  for (const geometry::Points& v : body.vertices) add(v.data(), sizeof(float) * static_cast<std::size_t>(v.size()));
  own.hash = content_hash(bytes);
}

motion::GeneratedBody own_body(const GeneratorConfig& config, const SceneSpec& spec) {
  const OwnBodyConfig& own = *config.body.own;
  import::ImportedBody in = *imported(own);  // a copy: first_frame takes its first frame off
  motion::GeneratedBody out{to_body(in), {}};
  const int transition = config.body.transition_frames, frames = config.frames;
  if (in.rigged() && own.garment_pose == "first_frame") {
    // The animation's first frame is the garments' pose; the motion follows it.
    if (in.frames.empty())
      throw InputError(own.file, "animation",
                       "an animation whose first frame is the garments' pose (garment_pose: first_frame)",
                       "no animation in the file");
    out.body.t_pose = body::pose_from_world(out.body.skeleton, in.frames[0].rotation, in.frames[0].position[0]);
    in.frames.erase(in.frames.begin());
  }
  if (spec.motion == kOwnAnimation && in.num_frames() < frames)
    throw InputError(own.file, in.animation.empty() ? "frames" : "animation '" + in.animation + "'",
                     "at least " + std::to_string(frames) + " frames at 30 fps (the config's frames" +
                         (own.garment_pose == "first_frame" && in.rigged() ? ", after the garments' pose)" : ")"),
                     std::to_string(in.num_frames()));
  if (!in.rigged()) {
    out.sequence = sequence_of_vertices(out.body, in, transition, frames);
    return out;
  }
  std::unique_ptr<motion::MotionSource> m;
  if (spec.motion == kOwnAnimation) {
    m = motion::with_t_pose_transition(file_animation(out.body, in, frames), out.body, transition);
  } else {
    std::string missing;
    for (const char* j : motion::kRetargetLegJoints)
      if (out.body.skeleton.index(j) < 0) missing += (missing.empty() ? "" : ", ") + std::string(j);
    if (!missing.empty())
      throw InputError(own.file, "skeleton", "the joints a BVH clip is retargeted onto (our names, e.g. Mixamo's)",
                       "no " + missing);
    if (out.body.soles[0].empty() || out.body.soles[1].empty())
      throw InputError(own.file, "soles",
                       "skin at the lowest point of the rest pose carried by each foot or toe joint (a BVH clip is "
                       "put on the ground by them)",
                       "none on the " + std::string(out.body.soles[0].empty() ? "left" : "right"));
    motion::MotionSpec ms;
    ms.motion = spec.motion;
    ms.frames = transition + frames;
    ms.seed = spec.seed;
    ms.transition_frames = transition;
    m = motion::make_motion(ms, out.body);
  }
  motion::SequenceOptions o;
  o.intersection.tolerance = config.body.intersection_tolerance_mm / 1000.0;
  o.intersection.gap = config.body.self_gap_mm / 1000.0;
  o.resolve = false;
  o.on_intersection = "keep";
  o.skin_untangle = config.body.skin_untangle.options();
  out.sequence = motion::generate_body_sequence(out.body, *m, o);
  return out;
}

}  // namespace layers::generate
