// A skinned, animated body as a binary glTF 2.0 file (see skinned_glb.h).
#include "layers/data/skinned_glb.h"

#include <Eigen/Geometry>
#include <cmath>

#include "glb_builder.h"
#include "layers/core/error.h"

namespace layers::data {

std::string skinned_glb_bytes(const SkinnedBody& body, double fps) {
  using glb::json;
  const std::size_t nj = body.joint_names.size(), nv = body.rest.size() / 3;
  if (nj == 0 || body.joint_parents.size() != nj || body.rest_joints.size() != nj * 3 ||
      body.skin_index.size() != nv * 4 || body.skin_weight.size() != nv * 4 || body.faces.empty() ||
      body.joints.size() % (nj * 12) != 0)
    throw Error("skinned glb: inconsistent array sizes");
  for (std::size_t j = 0; j < nj; ++j)
    if ((j == 0) != (body.joint_parents[j] < 0) || body.joint_parents[j] >= static_cast<std::int32_t>(j))
      throw Error("skinned glb: joint " + std::to_string(j) + " has parent " + std::to_string(body.joint_parents[j]));
  const std::size_t frames = body.joints.size() / (nj * 12);
  if (frames == 1) throw Error("skinned glb: an animation needs at least 2 frames");

  glb::Builder b;
  const auto rest_joint = [&](std::size_t j) {
    return Eigen::Vector3d(body.rest_joints[j * 3], body.rest_joints[j * 3 + 1], body.rest_joints[j * 3 + 2]);
  };
  json nodes = json::array();
  std::vector<json> children(nj, json::array());
  for (std::size_t j = 1; j < nj; ++j) children[static_cast<std::size_t>(body.joint_parents[j])].push_back(j);
  std::vector<float> inverse_bind;
  for (std::size_t j = 0; j < nj; ++j) {
    const int parent = body.joint_parents[j];
    const Eigen::Vector3d t =
        parent < 0 ? rest_joint(j) : Eigen::Vector3d(rest_joint(j) - rest_joint(static_cast<std::size_t>(parent)));
    json n = {{"name", body.joint_names[j]}, {"translation", {t.x(), t.y(), t.z()}}};
    if (!children[j].empty()) n["children"] = children[j];
    nodes.push_back(n);
    const Eigen::Vector3d p = rest_joint(j);
    // Column-major 4x4: identity with the translation -p.
    const float m[16] = {1,
                         0,
                         0,
                         0,
                         0,
                         1,
                         0,
                         0,
                         0,
                         0,
                         1,
                         0,
                         static_cast<float>(-p.x()),
                         static_cast<float>(-p.y()),
                         static_cast<float>(-p.z()),
                         1};
    inverse_bind.insert(inverse_bind.end(), m, m + 16);
  }
  const int position = b.vec3(body.rest);
  std::vector<std::uint16_t> joint_index(body.skin_index.begin(), body.skin_index.end());
  for (std::int32_t i : body.skin_index)
    if (i < 0 || static_cast<std::size_t>(i) >= nj)
      throw Error("skinned glb: skin index " + std::to_string(i) + " outside the joints");
  const int joints_0 =
      b.accessor(b.view(joint_index.data(), joint_index.size() * 2, glb::kArrayBuffer), glb::kUShort, nv, "VEC4");
  const int weights_0 = b.accessor(b.view(body.skin_weight.data(), body.skin_weight.size() * 4, glb::kArrayBuffer),
                                   glb::kFloat, nv, "VEC4");
  json primitive = {{"attributes", {{"POSITION", position}, {"JOINTS_0", joints_0}, {"WEIGHTS_0", weights_0}}},
                    {"indices", b.indices(body.faces)},
                    {"mode", 4}};
  const int mesh_node = static_cast<int>(nj);
  nodes.push_back({{"name", body.name}, {"mesh", 0}, {"skin", 0}});
  json joint_list = json::array();
  for (std::size_t j = 0; j < nj; ++j) joint_list.push_back(j);
  json skin = {{"joints", joint_list}, {"skeleton", 0}, {"inverseBindMatrices", b.floats(inverse_bind, "MAT4", false)}};

  json doc = {{"asset", {{"version", "2.0"}, {"generator", "layers tpose"}}},
              {"scene", 0},
              {"scenes", json::array({{{"nodes", {0, mesh_node}}}})},
              {"nodes", nodes},
              {"meshes", json::array({{{"name", body.name}, {"primitives", json::array({primitive})}}})},
              {"skins", json::array({skin})}};
  if (frames >= 2) {
    std::vector<float> times;
    for (std::size_t f = 0; f < frames; ++f) times.push_back(static_cast<float>(static_cast<double>(f) / fps));
    const int input = b.scalars(times, true);
    json samplers = json::array(), channels = json::array();
    const auto rotation = [&](std::size_t f, std::size_t j) {
      const float* m = body.joints.data() + (f * nj + j) * 12;
      Eigen::Matrix3d r;
      r << m[0], m[1], m[2], m[4], m[5], m[6], m[8], m[9], m[10];
      return Eigen::Quaterniond(r).normalized();
    };
    for (std::size_t j = 0; j < nj; ++j) {
      std::vector<float> q;
      Eigen::Quaterniond previous = Eigen::Quaterniond::Identity();
      for (std::size_t f = 0; f < frames; ++f) {
        const int parent = body.joint_parents[j];
        Eigen::Quaterniond local =
            parent < 0 ? rotation(f, j) : rotation(f, static_cast<std::size_t>(parent)).conjugate() * rotation(f, j);
        local.normalize();
        if (f > 0 && local.dot(previous) < 0) local.coeffs() *= -1.0;  // the short way between keys
        previous = local;
        q.insert(q.end(), {static_cast<float>(local.x()), static_cast<float>(local.y()), static_cast<float>(local.z()),
                           static_cast<float>(local.w())});
      }
      samplers.push_back({{"input", input}, {"output", b.floats(q, "VEC4", false)}, {"interpolation", "LINEAR"}});
      channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", j}, {"path", "rotation"}}}});
    }
    std::vector<float> root;
    for (std::size_t f = 0; f < frames; ++f) {
      const float* m = body.joints.data() + f * nj * 12;
      root.insert(root.end(), {m[3], m[7], m[11]});
    }
    samplers.push_back({{"input", input}, {"output", b.floats(root, "VEC3", false)}, {"interpolation", "LINEAR"}});
    channels.push_back({{"sampler", samplers.size() - 1}, {"target", {{"node", 0}, {"path", "translation"}}}});
    doc["animations"] = json::array({{{"name", "motion"}, {"channels", channels}, {"samplers", samplers}}});
  }
  doc["bufferViews"] = b.views;
  doc["accessors"] = b.accessors;
  return glb::container(std::move(doc), std::move(b.bin));
}

}  // namespace layers::data
