// A scene's body and outfit in the T-pose (see tpose.h).
#include "layers/generate/tpose.h"

#include "layers/body/body_arrays.h"
#include "layers/garment/garment_body.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"

namespace layers::generate {

TPoseMeshes tpose_meshes(const GeneratorConfig& config, int index) {
  SceneSimulation scene(config, sample_scene(config, index));
  TPoseMeshes out;
  out.problem = scene.problem();
  const garment::TPoseBody t_pose = garment::t_pose_body(scene.body().body);
  const geometry::Points& v = t_pose.mesh.vertices;
  out.body.positions.assign(v.data(), v.data() + v.size());
  out.body.faces = body::body_arrays(scene.body().body).faces;
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
  return out;
}

}  // namespace layers::generate
