// Loading the MPFB2 assets and building shaped bodies (see body_model.h).
#include "layers/body/body_model.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <map>
#include <mutex>

#include "json_file.h"
#include "layers/body/assets.h"
#include "layers/core/error.h"
#include "layers/geometry/obj.h"
#include "target_file.h"

namespace layers::body {
namespace {

constexpr double kDecimetre = 0.1;
constexpr double kCaucasianShare = 1.0 / 3.0;

// Where a bone end sits: the mean of a joint cube or of listed vertices.
struct JointRef {
  std::vector<int> vertices;
};

struct BoneDef {
  std::string name;
  std::string parent;
  JointRef head, tail;
  double roll = 0.0;
};

// MakeHuman's split of a macro value into (min, average, max) weights.
std::array<double, 3> macro_split(double v) {
  if (v < 0.5) {
    double lo = std::max(0.0, 1.0 - 2.0 * v);
    return {lo, 1.0 - lo, 0.0};
  }
  double hi = std::max(0.0, 2.0 * v - 1.0);
  return {0.0, 1.0 - hi, hi};
}

// Blender's vec_roll_to_mat3: the bone frame (columns x, y, z; y along
// `dir`) for a bone direction and roll, in Blender's z-up coordinates.
Mat3 blender_bone_frame(const Vec3& dir, double roll) {
  Vec3 n = dir.normalized();
  const double x = n.x(), y = n.y(), z = n.z();
  double theta = 1.0 + y;
  const double theta_alt = x * x + z * z;
  Mat3 b;
  if (theta > 6.1e-3 || theta_alt > 2.5e-4 * 2.5e-4) {
    if (theta <= 6.1e-3) theta = theta_alt * 0.5 + theta_alt * theta_alt * 0.125;
    // Columns: x axis, y axis (= dir), z axis.
    b.col(0) = Vec3(1.0 - x * x / theta, -x, -x * z / theta);
    b.col(1) = Vec3(x, y, z);
    b.col(2) = Vec3(-x * z / theta, -z, 1.0 - z * z / theta);
  } else {
    b = Mat3::Identity();
    b(0, 0) = -1.0;
    b(1, 1) = -1.0;
  }
  return axis_angle(n, roll).toRotationMatrix() * b;
}

// Blender world (z up, -y forward) <-> base mesh axes (y up, +z forward).
Vec3 to_blender(const Vec3& v) { return Vec3(v.x(), -v.z(), v.y()); }
const Mat3& blender_to_mesh() {
  static const Mat3 c = (Mat3() << 1, 0, 0, 0, 0, 1, 0, -1, 0).finished();
  return c;
}

std::vector<int> expand_ranges(const json::Value& ranges, const std::string& file, const std::string& what) {
  std::vector<int> out;
  for (const json::Value& r : json::array(ranges, file, what)) {
    const auto& pair = json::array(r, file, what);
    if (pair.size() != 2)
      throw InputError(file, what, "[first, last] ranges", std::to_string(pair.size()) + " numbers");
    int a = static_cast<int>(json::number(pair[0], file, what));
    int b = static_cast<int>(json::number(pair[1], file, what));
    for (int i = a; i <= b; ++i) out.push_back(i);
  }
  return out;
}

std::vector<std::string> target_names() {
  std::vector<std::string> names;
  const char* levels[] = {"min", "average", "max"};
  for (const char* g : {"female", "male"}) {
    for (const char* m : levels)
      for (const char* w : levels)
        names.push_back(std::string("universal-") + g + "-young-" + m + "muscle-" + w + "weight");
    names.push_back(std::string(g) + "-young-averagemuscle-averageweight-minheight");
    names.push_back(std::string(g) + "-young-averagemuscle-averageweight-maxheight");
    names.push_back(std::string("caucasian-") + g + "-young");
  }
  return names;
}

}  // namespace

std::vector<std::pair<std::string, double>> target_weights(const ShapeParams& s) {
  std::vector<std::pair<std::string, double>> out;
  auto add = [&](std::string name, double w) {
    if (w > 0.0) out.emplace_back(std::move(name), w);
  };
  const char* levels[] = {"min", "average", "max"};
  std::array<double, 3> muscle = macro_split(s.muscle), weight = macro_split(s.weight);
  const std::pair<const char*, double> genders[] = {{"female", 1.0 - s.gender}, {"male", s.gender}};
  for (const auto& [g, gw] : genders) {
    for (int m = 0; m < 3; ++m)
      for (int w = 0; w < 3; ++w)
        add(std::string("universal-") + g + "-young-" + levels[m] + "muscle-" + levels[w] + "weight",
            gw * muscle[m] * weight[w]);
    std::array<double, 3> height = macro_split(s.height);
    add(std::string(g) + "-young-averagemuscle-averageweight-minheight", gw * height[0]);
    add(std::string(g) + "-young-averagemuscle-averageweight-maxheight", gw * height[2]);
    add(std::string("caucasian-") + g + "-young", gw * kCaucasianShare);
  }
  return out;
}

double Body::stature() const {
  if (rest.vertices.rows() == 0) return 0.0;
  return static_cast<double>(rest.vertices.col(1).maxCoeff() - rest.vertices.col(1).minCoeff());
}

std::array<double, 2> sole_heights(const Body& body, const JointTransforms& transforms) {
  std::array<double, 2> h{};
  for (int side = 0; side < 2; ++side) {
    h[side] = std::numeric_limits<double>::infinity();
    for (const Vec3& p : skin_subset(body.rest.vertices, body.weights, body.skeleton, transforms, body.soles[side]))
      h[side] = std::min(h[side], p.y());
  }
  return h;
}

struct BodyModel::Impl {
  std::string root;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> base;  // all vertices, decimetres
  int num_skin = 0;
  geometry::Faces faces;
  std::vector<BoneDef> bones;  // parents first, root at 0
  std::vector<int> parents;
  SkinWeights weights;
  std::vector<Vec3> t_pose_euler;  // per bone, XYZ Euler (radians), Blender bone axes
  std::map<std::string, ShapeTarget> targets;
};

namespace {

JointRef read_joint_ref(const json::Value& end, const std::map<std::string, std::vector<int>>& groups,
                        const std::string& file, const std::string& what, int num_vertices) {
  JointRef ref;
  const std::string& strategy = json::string(json::member(end, "strategy", file), file, what + ".strategy");
  if (strategy == "CUBE") {
    const std::string& cube = json::string(json::member(end, "cube_name", file), file, what + ".cube_name");
    auto it = groups.find(cube);
    if (it == groups.end())
      throw InputError(file, what + ".cube_name", "a vertex group of the base mesh", "'" + cube + "'");
    ref.vertices = it->second;
  } else if (strategy == "MEAN") {
    for (const json::Value& v : json::array(json::member(end, "vertex_indices", file), file, what + ".vertex_indices"))
      ref.vertices.push_back(static_cast<int>(json::number(v, file, what + ".vertex_indices")));
  } else {
    throw InputError(file, what + ".strategy", "CUBE or MEAN", "'" + strategy + "'");
  }
  for (int v : ref.vertices)
    if (v < 0 || v >= num_vertices) throw InputError(file, what, "vertex indices of the base mesh", std::to_string(v));
  if (ref.vertices.empty()) throw InputError(file, what, "at least one vertex", "none");
  return ref;
}

// Orders bones parents-first (depth first from the single root, children
// in file order).
std::vector<BoneDef> order_bones(std::vector<BoneDef> defs, const std::string& file) {
  std::vector<BoneDef> out;
  std::vector<bool> used(defs.size(), false);
  std::function<void(const std::string&)> visit = [&](const std::string& parent) {
    for (std::size_t i = 0; i < defs.size(); ++i) {
      if (used[i] || defs[i].parent != parent) continue;
      used[i] = true;
      out.push_back(defs[i]);
      visit(defs[i].name);
    }
  };
  visit("");
  if (out.empty() || std::count_if(defs.begin(), defs.end(), [](const BoneDef& b) { return b.parent.empty(); }) != 1)
    throw InputError(file, "", "exactly one root bone (empty parent)", "none or several");
  if (out.size() != defs.size())
    throw InputError(file, "", "every bone's parent to be a bone of the rig", "unreachable bones");
  return out;
}

}  // namespace

BodyModel::BodyModel(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
BodyModel::~BodyModel() = default;

const std::string& BodyModel::asset_root() const { return impl_->root; }
int BodyModel::num_skin_vertices() const { return impl_->num_skin; }

std::shared_ptr<const BodyModel> BodyModel::load(const std::string& asset_root) {
  static std::mutex mutex;
  static std::map<std::string, std::shared_ptr<const BodyModel>> cache;
  const std::string root = resolve_asset_root(asset_root);
  std::lock_guard<std::mutex> lock(mutex);
  if (auto it = cache.find(root); it != cache.end()) return it->second;

  auto impl = std::make_unique<Impl>();
  impl->root = root;
  const std::string dir = body_asset_dir(root);

  // Base mesh.
  const std::string obj_path = dir + "/base.obj";
  const geometry::ObjPolygons obj = geometry::read_obj_polygons(obj_path);
  const int nv = obj.num_vertices();
  impl->base = Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>>(obj.positions.data(), nv, 3);

  // Vertex groups: the skin range and the joint cubes.
  const std::string groups_path = dir + "/basemesh_vertex_groups.json";
  json::Value groups_json = json::parse_file(groups_path);
  if (!groups_json.is_object()) throw InputError(groups_path, "", "an object of vertex groups", "something else");
  std::map<std::string, std::vector<int>> groups;
  for (const auto& item : groups_json.items())
    groups[item.key()] = expand_ranges(item.value(), groups_path, item.key());
  const std::vector<int>& skin = groups["body"];
  for (std::size_t i = 0; i < skin.size(); ++i)
    if (skin[i] != static_cast<int>(i))
      throw InputError(groups_path, "body", "the range [0, n) of skin vertices", "a different layout");
  if (skin.empty() || static_cast<int>(skin.size()) > nv)
    throw InputError(groups_path, "body", "between 1 and " + std::to_string(nv) + " vertices",
                     std::to_string(skin.size()));
  impl->num_skin = static_cast<int>(skin.size());

  // Skin faces: all vertices on the skin; polygons fanned into triangles
  // (quads split along their shorter diagonal in the base mesh).
  std::vector<std::array<int, 3>> tris;
  for (int f = 0; f < obj.num_faces(); ++f) {
    const int* idx = obj.indices.data() + obj.face_start[f];
    const int n = obj.face_start[f + 1] - obj.face_start[f];
    if (std::any_of(idx, idx + n, [&](int v) { return v >= impl->num_skin; })) continue;
    int first = 0;
    if (n == 4) {
      double d02 = (impl->base.row(idx[0]) - impl->base.row(idx[2])).norm();
      double d13 = (impl->base.row(idx[1]) - impl->base.row(idx[3])).norm();
      first = d13 < d02 ? 1 : 0;
    }
    for (int k = 1; k + 1 < n; ++k) tris.push_back({idx[first], idx[(first + k) % n], idx[(first + k + 1) % n]});
  }
  impl->faces.resize(static_cast<Eigen::Index>(tris.size()), 3);
  for (std::size_t i = 0; i < tris.size(); ++i)
    for (int k = 0; k < 3; ++k) impl->faces(static_cast<Eigen::Index>(i), k) = tris[i][k];

  // Rig.
  const std::string rig_path = dir + "/rig.cmu_mb.json";
  json::Value rig = json::parse_file(rig_path);
  if (!rig.is_object()) throw InputError(rig_path, "", "an object of bones", "something else");
  std::vector<BoneDef> defs;
  for (const auto& item : rig.items()) {
    const std::string& name = item.key();
    const json::Value& bone = item.value();
    BoneDef d;
    d.name = name;
    d.parent = json::string(json::member(bone, "parent", rig_path), rig_path, name + ".parent");
    d.head = read_joint_ref(json::member(bone, "head", rig_path), groups, rig_path, name + ".head", nv);
    d.tail = read_joint_ref(json::member(bone, "tail", rig_path), groups, rig_path, name + ".tail", nv);
    d.roll = json::number(json::member(bone, "roll", rig_path), rig_path, name + ".roll");
    defs.push_back(std::move(d));
  }
  impl->bones = order_bones(std::move(defs), rig_path);
  std::map<std::string, int> bone_index;
  for (std::size_t i = 0; i < impl->bones.size(); ++i) bone_index[impl->bones[i].name] = static_cast<int>(i);
  for (const BoneDef& b : impl->bones) impl->parents.push_back(b.parent.empty() ? -1 : bone_index[b.parent]);

  // Skinning weights: the four largest per skin vertex, renormalised.
  const std::string weights_path = dir + "/weights.cmu_mb.json";
  json::Value weights_json = json::parse_file(weights_path);
  std::vector<std::vector<std::pair<float, int>>> influences(impl->num_skin);
  for (const auto& item :
       json::object(json::member(weights_json, "weights", weights_path), weights_path, "weights").items()) {
    const std::string& bone = item.key();
    const json::Value& list = item.value();
    auto it = bone_index.find(bone);
    if (it == bone_index.end())
      throw InputError(weights_path, "weights." + bone, "a bone of the rig", "'" + bone + "'");
    for (const json::Value& pair : json::array(list, weights_path, "weights." + bone)) {
      const auto& vw = json::array(pair, weights_path, "weights." + bone);
      if (vw.size() != 2)
        throw InputError(weights_path, "weights." + bone, "[vertex, weight] pairs",
                         std::to_string(vw.size()) + " numbers");
      int v = static_cast<int>(json::number(vw[0], weights_path, "weights." + bone));
      double w = json::number(vw[1], weights_path, "weights." + bone);
      if (v < 0 || v >= nv)
        throw InputError(weights_path, "weights." + bone, "vertex indices of the base mesh", std::to_string(v));
      if (v < impl->num_skin && w > 0.0) influences[v].emplace_back(static_cast<float>(w), it->second);
    }
  }
  impl->weights.index.setZero(impl->num_skin, 4);
  impl->weights.weight.setZero(impl->num_skin, 4);
  int unweighted = 0;
  for (int v = 0; v < impl->num_skin; ++v) {
    auto& list = influences[v];
    std::sort(list.begin(), list.end(), [](const auto& a, const auto& b) {
      return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    if (list.size() > 4) list.resize(4);
    float sum = 0.0f;
    for (const auto& [w, j] : list) sum += w;
    if (list.empty() || sum <= 0.0f) {
      ++unweighted;
      impl->weights.weight(v, 0) = 1.0f;  // follows the root
      continue;
    }
    for (std::size_t k = 0; k < list.size(); ++k) {
      impl->weights.index(v, static_cast<Eigen::Index>(k)) = list[k].second;
      impl->weights.weight(v, static_cast<Eigen::Index>(k)) = list[k].first / sum;
    }
  }
  if (unweighted > 0)
    throw InputError(weights_path, "weights", "a weight for every skin vertex",
                     std::to_string(unweighted) + " skin vertices without one");

  // T-pose: per-bone XYZ Euler angles in Blender bone axes.
  const std::string tpose_path = dir + "/t-pose.cmu_mb.json";
  json::Value tpose = json::parse_file(tpose_path);
  impl->t_pose_euler.assign(impl->bones.size(), Vec3::Zero());
  for (const auto& item :
       json::object(json::member(tpose, "bone_rotations", tpose_path), tpose_path, "bone_rotations").items()) {
    const std::string& bone = item.key();
    const json::Value& angles = item.value();
    auto it = bone_index.find(bone);
    if (it == bone_index.end())
      throw InputError(tpose_path, "bone_rotations." + bone, "a bone of the rig", "'" + bone + "'");
    const auto& a = json::array(angles, tpose_path, "bone_rotations." + bone);
    if (a.size() != 3) throw InputError(tpose_path, "bone_rotations." + bone, "3 angles", std::to_string(a.size()));
    for (int k = 0; k < 3; ++k)
      impl->t_pose_euler[it->second][k] = json::number(a[k], tpose_path, "bone_rotations." + bone);
  }

  // Shape targets (parsed once, kept for every build()).
  for (const std::string& name : target_names())
    impl->targets[name] = read_target(dir + "/targets/" + name + ".target.gz", nv);

  std::shared_ptr<const BodyModel> model(new BodyModel(std::move(impl)));
  cache[root] = model;
  return model;
}

Body BodyModel::build(const ShapeParams& shape) const {
  const Impl& m = *impl_;
  for (double v : {shape.gender, shape.muscle, shape.weight, shape.height})
    if (!(v >= 0.0 && v <= 1.0)) throw InputError("body shape", "", "parameters in [0, 1]", std::to_string(v));

  // Blend targets over all base vertices (joint cubes included).
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> shaped = m.base;
  for (const auto& [name, w] : target_weights(shape)) {
    const ShapeTarget& t = m.targets.at(name);
    for (std::size_t i = 0; i < t.vertex.size(); ++i)
      for (int k = 0; k < 3; ++k) shaped(t.vertex[i], k) += w * static_cast<double>(t.offset[3 * i + k]);
  }
  shaped *= kDecimetre;

  Body body;
  body.shape = shape;
  const double ground = shaped.topRows(m.num_skin).col(1).minCoeff();
  const Vec3 lift(0.0, -ground, 0.0);
  body.rest.vertices.resize(m.num_skin, 3);
  for (int v = 0; v < m.num_skin; ++v)
    body.rest.vertices.row(v) = (shaped.row(v).transpose() + lift).transpose().cast<float>();
  body.rest.faces = m.faces;

  auto place = [&](const JointRef& ref) {
    Vec3 sum = Vec3::Zero();
    for (int v : ref.vertices) sum += shaped.row(v).transpose();
    return Vec3(sum / static_cast<double>(ref.vertices.size()) + lift);
  };
  Skeleton& sk = body.skeleton;
  for (std::size_t b = 0; b < m.bones.size(); ++b) {
    const BoneDef& def = m.bones[b];
    sk.names.push_back(def.name);
    sk.parents.push_back(m.parents[b]);
    sk.rest_head.push_back(place(def.head));
    sk.rest_tail.push_back(place(def.tail));
    Vec3 dir = to_blender(sk.rest_tail.back() - sk.rest_head.back());
    sk.bone_frame.push_back(blender_to_mesh() * blender_bone_frame(dir, def.roll));
  }
  body.weights = m.weights;

  body.t_pose = rest_pose(sk);
  for (int j = 0; j < sk.num_joints(); ++j) {
    const Vec3& e = m.t_pose_euler[j];
    const double zyx[3] = {e.z(), e.y(), e.x()};  // Blender XYZ Euler = Rz * Ry * Rx
    body.t_pose.local[j] = from_bone_axes(sk, j, euler("ZYX", zyx));
  }

  body.soles = sole_vertices(body);
  // The T-pose straightens the legs: put its soles back on the ground.
  auto t_soles = sole_heights(body, forward_kinematics(sk, body.t_pose));
  body.t_pose.root.y() -= std::min(t_soles[0], t_soles[1]);
  return body;
}

std::array<std::vector<int>, 2> sole_vertices(const Body& body) {
  std::array<std::vector<int>, 2> soles;
  if (body.rest.num_vertices() == 0) return soles;
  const double ground = body.rest.vertices.col(1).minCoeff();
  const char* feet[2][2] = {{"LeftFoot", "LeftToeBase"}, {"RightFoot", "RightToeBase"}};
  for (int side = 0; side < 2; ++side) {
    const int a = body.skeleton.index(feet[side][0]), b = body.skeleton.index(feet[side][1]);
    if (a < 0 && b < 0) continue;
    for (int v = 0; v < body.weights.num_vertices(); ++v) {
      const int dominant = body.weights.index(v, 0);
      if ((dominant == a || dominant == b) && body.rest.vertices(v, 1) < ground + kSoleHeight) soles[side].push_back(v);
    }
  }
  return soles;
}

}  // namespace layers::body
