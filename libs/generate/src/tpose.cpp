// A scene's body and outfit in the T-pose (see tpose.h).
#include "layers/generate/tpose.h"

#include "layers/body/body_arrays.h"
#include "layers/body/skinning.h"
#include "layers/garment/garment_body.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"
#include "layers/import/body_import.h"
#include "layers/motion/body_sequence.h"

namespace layers::generate {

TPoseMeshes tpose_meshes(const GeneratorConfig& config, int index) {
  SceneSimulation scene(config, sample_scene(config, index));
  TPoseMeshes out;
  out.problem = scene.problem();
  const garment::TPoseBody t_pose = garment::t_pose_body(scene.body().body);
  const geometry::Points& v = t_pose.mesh.vertices;
  out.body.positions.assign(v.data(), v.data() + v.size());
  const body::BodyArrays arrays = body::body_arrays(scene.body().body);
  out.body.faces = arrays.faces;
  const Eigen::Isometry3d back = scene.placement().inverse();
  for (const data::GarmentData& g : scene.garments()) {
    data::ObjMesh m;
    m.faces = g.faces;
    m.uv = g.uv;
    m.uv_faces = g.uv_faces;
    for (std::size_t i = 0; i + 2 < g.rest.size(); i += 3) {
      const Eigen::Vector3d p = back * Eigen::Vector3d(g.rest[i], g.rest[i + 1], g.rest[i + 2]);
      m.positions.insert(m.positions.end(),
                         {static_cast<float>(p.x()), static_cast<float>(p.y()), static_cast<float>(p.z())});
    }
    out.garments.emplace_back(g.name, std::move(m));
  }
  // The rig: none for a user's mesh sequence (its one joint is a fit).
  const std::string& file = scene.body().body.file;
  if (file.empty() || !import::is_mesh_sequence(file)) {
    out.rig.rest = arrays.rest_vertices;
    out.rig.faces = arrays.faces;
    out.rig.joint_names = arrays.joint_names;
    out.rig.joint_parents = arrays.joint_parents;
    out.rig.rest_joints = arrays.rest_joints;
    out.rig.skin_index = arrays.skin_index;
    out.rig.skin_weight = arrays.skin_weight;
    const body::Body& b = scene.body().body;
    const motion::BodySequence& s = scene.body().sequence;
    const std::size_t per_frame = static_cast<std::size_t>(s.num_joints) * 12;
    out.rig.joints.resize(per_frame);
    body::joint_matrices(body::forward_kinematics(b.skeleton, b.t_pose), out.rig.joints.data());
    const std::size_t first = static_cast<std::size_t>(std::min(config.body.transition_frames, s.num_frames));
    out.rig.joints.insert(out.rig.joints.end(), s.joints.begin() + static_cast<std::ptrdiff_t>(first * per_frame),
                          s.joints.end());
  }
  return out;
}

}  // namespace layers::generate
