// A user's rigged body read with assimp: skinned meshes, skeleton, weights
// and one animation sampled at 30 fps (see body_import.h).
#include "layers/import/body_import.h"

#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/Importer.hpp>

#include <Eigen/LU>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>

#include "assimp_read.h"
#include "body_checks.h"
#include "layers/core/error.h"
#include "layers/data/format.h"

namespace layers::import {
namespace {

using Mat4 = Eigen::Matrix4d;

constexpr double kRigidTolerance = 1e-3;  // |L^T L - I| of a joint's skinning matrix
// m a joint may stray from its fixed offset to its parent: real rigs carry
// small translation keys (CesiumMan's move by up to 3.0 mm); the body
// follows joint rotations and the root's motion, so such a joint is taken
// at its offset (the largest drift is kept for a warning), and a larger
// one is refused.
constexpr double kOffsetTolerance = 5e-3;
constexpr double kMaxSeconds = 3600;  // the longest animation read (as a BVH clip's bound)
// The most joints x sampled frames read: each costs about 120 bytes while
// sampled and kept (a 53 KB GLB of 250 joints keyed at 0 and 3600 s took
// 3.24 GB), so this bound keeps a body under about 0.5 GB: an hour at 30
// fps for 37 joints, ten minutes for 222.
constexpr long kMaxJointFrames = 4000000;
constexpr float kSameWeight = 1e-5f;  // weights of two seam copies that may be welded

Mat4 to_eigen(const aiMatrix4x4& m) {
  Mat4 r;
  r << m.a1, m.a2, m.a3, m.a4, m.b1, m.b2, m.b3, m.b4, m.c1, m.c2, m.c3, m.c4, m.d1, m.d2, m.d3, m.d4;
  return r;
}

std::string strip_namespace(const std::string& name) {
  const std::size_t colon = name.rfind(':');
  return colon == std::string::npos ? name : name.substr(colon + 1);
}

// The skeleton: bound nodes in depth-first order, each with the nearest
// bound ancestor as parent.
struct Rig {
  std::vector<const aiNode*> nodes;
  std::vector<int> parents;
  std::map<std::string, int> index;  // file name -> joint
};

void walk(const aiNode* node, int parent, const std::set<std::string>& bound, Rig& rig) {
  int here = parent;
  const std::string name = node->mName.C_Str();
  if (bound.count(name) && !rig.index.count(name)) {
    here = static_cast<int>(rig.nodes.size());
    rig.index[name] = here;
    rig.nodes.push_back(node);
    rig.parents.push_back(parent);
  }
  for (unsigned c = 0; c < node->mNumChildren; ++c) walk(node->mChildren[c], here, bound, rig);
}

// World transform of every node, with `local` giving each node's own.
template <class Local>
void world_transforms(const aiNode* node, const Mat4& parent, const Local& local, std::map<const aiNode*, Mat4>& out) {
  const Mat4 world = parent * local(node);
  out[node] = world;
  for (unsigned c = 0; c < node->mNumChildren; ++c) world_transforms(node->mChildren[c], world, local, out);
}

// A key track sampled at `t` (ticks): clamped at the ends, linear between.
template <class Key, class Mix>
auto sample(const Key* keys, unsigned n, double t, const Mix& mix) {
  if (n == 1 || t <= keys[0].mTime) return keys[0].mValue;
  if (t >= keys[n - 1].mTime) return keys[n - 1].mValue;
  unsigned k = 1;
  while (k < n - 1 && keys[k].mTime < t) ++k;
  const double span = keys[k].mTime - keys[k - 1].mTime;
  const double s = span > 0 ? (t - keys[k - 1].mTime) / span : 0.0;
  return mix(keys[k - 1].mValue, keys[k].mValue, s);
}

Mat4 channel_transform(const aiNodeAnim* ch, double t) {
  const auto lerp = [](const aiVector3D& a, const aiVector3D& b, double s) {
    return a + (b - a) * static_cast<ai_real>(s);
  };
  const auto slerp = [](const aiQuaternion& a, const aiQuaternion& b, double s) {
    aiQuaternion q;
    aiQuaternion::Interpolate(q, a, b, static_cast<ai_real>(s));
    return q;
  };
  const aiVector3D p = ch->mNumPositionKeys ? sample(ch->mPositionKeys, ch->mNumPositionKeys, t, lerp) : aiVector3D();
  const aiQuaternion r =
      ch->mNumRotationKeys ? sample(ch->mRotationKeys, ch->mNumRotationKeys, t, slerp) : aiQuaternion();
  const aiVector3D s =
      ch->mNumScalingKeys ? sample(ch->mScalingKeys, ch->mNumScalingKeys, t, lerp) : aiVector3D(1, 1, 1);
  Mat4 m = Mat4::Identity();
  m.topLeftCorner<3, 3>() = Eigen::Quaterniond(r.w, r.x, r.y, r.z).normalized().toRotationMatrix() *
                            Eigen::Vector3d(s.x, s.y, s.z).asDiagonal();
  m.topRightCorner<3, 1>() = Eigen::Vector3d(p.x, p.y, p.z);
  return m;
}

const aiAnimation* choose_animation(const aiScene* scene, const std::string& path, const std::string& name) {
  if (scene->mNumAnimations == 0) {
    if (!name.empty()) throw InputError(path, "animation", "an animation named '" + name + "'", "no animation");
    return nullptr;
  }
  if (name.empty()) return scene->mAnimations[0];
  std::string names;
  for (unsigned a = 0; a < scene->mNumAnimations; ++a) {
    const std::string n = scene->mAnimations[a]->mName.C_Str();
    if (n == name) return scene->mAnimations[a];
    names += (names.empty() ? "'" : ", '") + n + "'";
  }
  throw InputError(path, "animation", "one of " + names, "'" + name + "'");
}

// The four largest influences, renormalised; false when there is none.
bool top_four(std::vector<std::pair<float, int>> w, std::array<int, 4>& index, std::array<float, 4>& weight) {
  std::sort(w.begin(), w.end(), [](const auto& a, const auto& b) {
    return a.first > b.first || (a.first == b.first && a.second < b.second);
  });
  if (w.size() > 4) w.resize(4);
  float total = 0;
  for (const auto& x : w) total += std::max(0.0f, x.first);
  if (!(total > 0)) return false;
  index.fill(0);
  weight.fill(0.0f);
  for (std::size_t k = 0; k < w.size(); ++k) {
    index[k] = w[k].second;
    weight[k] = std::max(0.0f, w[k].first) / total;
  }
  return true;
}

}  // namespace

ImportedBody import_rigged_body(const std::string& path, double scale, const std::string& animation) {
  if (!std::filesystem::is_regular_file(path))
    throw InputError(path, "", "a rigged body file (glTF/GLB, FBX, Collada, ...)", "no such file");
  if (!(scale > 0) || !std::isfinite(scale))
    throw InputError(path, "scale", "a positive factor to metres", std::to_string(scale));
  Assimp::Importer importer;
  const aiScene* scene = detail::read_with_assimp(importer, path, aiProcess_Triangulate | aiProcess_SortByPType,
                                                  "a body file assimp reads");

  // The meshes bound to joints, and the nodes holding them.
  std::set<std::string> bound;
  std::vector<std::pair<const aiMesh*, const aiNode*>> meshes;
  ImportedBody out;
  out.file = path;
  std::map<const aiNode*, Mat4> rest_world;
  world_transforms(
      scene->mRootNode, Mat4::Identity(), [](const aiNode* n) { return to_eigen(n->mTransformation); }, rest_world);
  for (const auto& [node, world] : rest_world) {
    for (unsigned k = 0; k < node->mNumMeshes; ++k) {
      const aiMesh* m = scene->mMeshes[node->mMeshes[k]];
      if (!(m->mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) continue;
      if (!m->HasBones()) {
        ++out.skipped_meshes;
        continue;
      }
      meshes.emplace_back(m, node);
      for (unsigned b = 0; b < m->mNumBones; ++b) bound.insert(m->mBones[b]->mName.C_Str());
    }
  }
  if (meshes.empty()) throw InputError(path, "", "a mesh skinned to a skeleton", "no skinned mesh");
  // Meshes in a fixed order (the node map is ordered by address).
  std::sort(meshes.begin(), meshes.end(), [&](const auto& a, const auto& b) {
    return std::find(scene->mMeshes, scene->mMeshes + scene->mNumMeshes, a.first) <
           std::find(scene->mMeshes, scene->mMeshes + scene->mNumMeshes, b.first);
  });

  Rig rig;
  walk(scene->mRootNode, -1, bound, rig);
  const int joints = static_cast<int>(rig.nodes.size());
  if (joints < static_cast<int>(bound.size()))
    throw InputError(path, "skeleton", "every bone a node of the scene",
                     std::to_string(bound.size() - joints) + " bones without a node");
  std::string roots;
  int n_roots = 0;
  for (int j = 0; j < joints; ++j)
    if (rig.parents[j] < 0) {
      ++n_roots;
      roots += (roots.empty() ? "'" : ", '") + std::string(rig.nodes[j]->mName.C_Str()) + "'";
    }
  if (n_roots != 1) throw InputError(path, "skeleton", "one root joint", std::to_string(n_roots) + " (" + roots + ")");
  for (int j = 0; j < joints; ++j) {
    out.joint_names.push_back(strip_namespace(rig.nodes[j]->mName.C_Str()));
    out.parents.push_back(rig.parents[j]);
    for (int k = 0; k < j; ++k)
      if (out.joint_names[k] == out.joint_names[j])
        throw InputError(path, "skeleton", "distinct joint names (after the namespace, e.g. 'mixamorig:')",
                         "'" + std::string(rig.nodes[k]->mName.C_Str()) + "' and '" + rig.nodes[j]->mName.C_Str() +
                             "' both named '" + out.joint_names[j] + "'");
  }

  // Bind pose of each joint in the world, from the first mesh bound to it.
  // By glTF's rule a skinned vertex is placed by its joints alone (joint
  // world matrix times inverse bind matrix, the mesh node's own transform
  // ignored): where the joints' rest world matrices times their offsets
  // agree (A, the skin's space to the world: an armature's Y-up turn and
  // 0.01 scale as Blender and Mixamo write them), the mesh is placed by A
  // and each joint binds at its rest world matrix. Otherwise (a file whose
  // rest pose is not its bind pose) assimp's rule: the mesh's node
  // transform times the bone's inverse offset.
  std::vector<Mat4> bind(joints), bind_inverse(joints);
  std::vector<char> have(joints, 0);
  struct FileVertex {
    std::array<float, 3> p;
    std::array<int, 4> index;
    std::array<float, 4> weight;
  };
  std::vector<FileVertex> vertices;
  std::vector<std::array<int, 3>> faces;
  for (const auto& [m, node] : meshes) {
    Mat4 g = rest_world.at(node);
    bool by_joints = m->mNumBones > 0;
    Mat4 skin_to_world = Mat4::Identity();
    for (unsigned b = 0; b < m->mNumBones && by_joints; ++b) {
      const aiBone* bone = m->mBones[b];
      const Mat4 a = rest_world.at(rig.nodes[rig.index.at(bone->mName.C_Str())]) * to_eigen(bone->mOffsetMatrix);
      if (b == 0)
        skin_to_world = a;
      else
        by_joints = (a - skin_to_world).cwiseAbs().maxCoeff() <= 1e-5 * (1 + skin_to_world.cwiseAbs().maxCoeff());
    }
    if (by_joints) g = skin_to_world;
    std::vector<std::vector<std::pair<float, int>>> influence(m->mNumVertices);
    for (unsigned b = 0; b < m->mNumBones; ++b) {
      const aiBone* bone = m->mBones[b];
      const int j = rig.index.at(bone->mName.C_Str());
      if (!have[j]) {
        bind[j] = g * to_eigen(bone->mOffsetMatrix).inverse();
        bind_inverse[j] = bind[j].inverse();
        have[j] = 1;
      }
      for (unsigned w = 0; w < bone->mNumWeights; ++w)
        if (bone->mWeights[w].mVertexId < m->mNumVertices)
          influence[bone->mWeights[w].mVertexId].emplace_back(bone->mWeights[w].mWeight, j);
    }
    const int base = static_cast<int>(vertices.size());
    for (unsigned v = 0; v < m->mNumVertices; ++v) {
      const Eigen::Vector4d p = g * Eigen::Vector4d(m->mVertices[v].x, m->mVertices[v].y, m->mVertices[v].z, 1.0);
      FileVertex fv;
      for (int a = 0; a < 3; ++a) fv.p[a] = static_cast<float>(p[a] * scale);
      if (!top_four(influence[v], fv.index, fv.weight))
        throw InputError(path, std::string("mesh '") + m->mName.C_Str() + "'", "a bone weight on every vertex",
                         "vertex " + std::to_string(v) + " has none");
      vertices.push_back(fv);
    }
    for (unsigned f = 0; f < m->mNumFaces; ++f)
      if (m->mFaces[f].mNumIndices == 3)
        faces.push_back({base + static_cast<int>(m->mFaces[f].mIndices[0]),
                         base + static_cast<int>(m->mFaces[f].mIndices[1]),
                         base + static_cast<int>(m->mFaces[f].mIndices[2])});
  }
  for (const FileVertex& v : vertices)
    for (float x : v.p)
      if (!std::isfinite(x)) throw InputError(path, "vertices", "finite positions", "a non-finite value");

  // Welding: copies of a vertex at one position with the same weights
  // (split by the file at UV or normal seams) become one.
  std::map<std::array<float, 3>, std::vector<int>> at;
  std::vector<int> welded(vertices.size());
  std::vector<int> kept;
  for (std::size_t i = 0; i < vertices.size(); ++i) {
    std::vector<int>& same = at[vertices[i].p];
    int found = -1;
    for (int k : same) {
      const FileVertex& o = vertices[static_cast<std::size_t>(kept[static_cast<std::size_t>(k)])];
      bool equal = o.index == vertices[i].index;
      for (int s = 0; s < 4 && equal; ++s) equal = std::abs(o.weight[s] - vertices[i].weight[s]) <= kSameWeight;
      if (equal) found = k;
    }
    if (found < 0) {
      found = static_cast<int>(kept.size());
      kept.push_back(static_cast<int>(i));
      same.push_back(found);
    }
    welded[i] = found;
  }
  const auto nv = static_cast<Eigen::Index>(kept.size());
  out.rest.vertices.resize(nv, 3);
  out.skin_index.resize(nv, 4);
  out.skin_weight.resize(nv, 4);
  for (Eigen::Index v = 0; v < nv; ++v) {
    const FileVertex& fv = vertices[static_cast<std::size_t>(kept[static_cast<std::size_t>(v)])];
    for (int a = 0; a < 3; ++a) out.rest.vertices(v, a) = fv.p[a];
    for (int s = 0; s < 4; ++s) {
      out.skin_index(v, s) = fv.index[s];
      out.skin_weight(v, s) = fv.weight[s];
    }
  }
  out.rest.faces.resize(static_cast<Eigen::Index>(faces.size()), 3);
  for (std::size_t f = 0; f < faces.size(); ++f)
    for (int a = 0; a < 3; ++a)
      out.rest.faces(static_cast<Eigen::Index>(f), a) = welded[static_cast<std::size_t>(faces[f][a])];
  for (int j = 0; j < joints; ++j) out.joint_rest.push_back(bind[j].topRightCorner<3, 1>() * scale);
  check_body_height(out.rest, path);

  // The animation, sampled at 30 fps.
  const aiAnimation* anim = choose_animation(scene, path, animation);
  if (!anim) return out;
  out.animation = anim->mName.C_Str();
  std::map<std::string, const aiNodeAnim*> channels;
  for (unsigned c = 0; c < anim->mNumChannels; ++c)
    channels[anim->mChannels[c]->mNodeName.C_Str()] = anim->mChannels[c];
  const double ticks_per_second = anim->mTicksPerSecond > 0 ? anim->mTicksPerSecond : 25.0;
  const double seconds = anim->mDuration / ticks_per_second;
  if (!std::isfinite(seconds) || seconds < 0 || seconds > kMaxSeconds)
    throw InputError(path, "animation '" + out.animation + "'", "a duration of 0-3600 s",
                     std::to_string(seconds) + " s");
  const double fps = static_cast<double>(data::kFps);
  const int n_frames = static_cast<int>(std::floor(seconds * fps + 1e-6)) + 1;
  if (static_cast<long>(n_frames) * joints > kMaxJointFrames)
    throw InputError(path, "animation '" + out.animation + "'",
                     "at most " + std::to_string(kMaxJointFrames) +
                         " joints x frames at 30 fps (name a shorter animation with body.own.animation, or cut it)",
                     std::to_string(joints) + " joints x " + std::to_string(n_frames) + " frames (" +
                         std::to_string(seconds) + " s)");
  std::map<const aiNode*, Mat4> world;
  for (int f = 0; f < n_frames; ++f) {
    const double t = f / fps * ticks_per_second;
    world.clear();
    world_transforms(
        scene->mRootNode, Mat4::Identity(),
        [&](const aiNode* n) {
          const auto it = channels.find(n->mName.C_Str());
          return it == channels.end() ? to_eigen(n->mTransformation) : channel_transform(it->second, t);
        },
        world);
    BodyFrame frame;
    for (int j = 0; j < joints; ++j) {
      const Mat4 a = world.at(rig.nodes[j]);
      const Eigen::Matrix3d l = (a * bind_inverse[j]).topLeftCorner<3, 3>();
      const double off = (l.transpose() * l - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff();
      if (!(off <= kRigidTolerance) || !(l.determinant() > 0))
        throw InputError(path, "animation '" + out.animation + "'", "joints that rotate and move only (rigid skinning)",
                         "joint '" + out.joint_names[j] + "' scaled or sheared in frame " + std::to_string(f));
      frame.rotation.push_back(Eigen::Quaterniond(l).normalized());
      frame.position.push_back(a.topRightCorner<3, 1>() * scale);
      if (!frame.position.back().allFinite())
        throw InputError(path, "animation '" + out.animation + "'", "finite joint positions",
                         "a non-finite value in frame " + std::to_string(f));
      // Only the root moves on its own: a joint stays at its bind offset
      // from its parent, turned with it (the body/joints convention).
      const int p = out.parents[j];
      if (p >= 0) {
        const Eigen::Vector3d fixed = frame.position[p] + frame.rotation[p] * (out.joint_rest[j] - out.joint_rest[p]);
        const double off = (frame.position.back() - fixed).norm();
        if (off > out.joint_drift) {
          out.joint_drift = off;
          out.drift_joint = out.joint_names[j];
          out.drift_frame = f;
        }
        if (off > kOffsetTolerance) {
          char mm[32];
          std::snprintf(mm, sizeof mm, "%.1f", off * 1000);
          throw InputError(path, "animation '" + out.animation + "'",
                           "joints that keep their offset from their parent within 5 mm (only the root may move; "
                           "remove the other joints' translation keys)",
                           "joint '" + out.joint_names[j] + "' " + mm + " mm off it in frame " + std::to_string(f));
        }
      }
    }
    out.frames.push_back(std::move(frame));
  }
  return out;
}

ImportedBody import_body(const std::string& path, const std::string& mesh, double scale, const std::string& animation) {
  return is_mesh_sequence(path) ? import_mesh_sequence(path, mesh, scale) : import_rigged_body(path, scale, animation);
}

}  // namespace layers::import
