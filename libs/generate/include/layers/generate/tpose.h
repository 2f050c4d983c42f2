// layers/generate/tpose.h -- a generator config's scene in the T-pose its
// garments are fitted in (`layers tpose`): the body and the outfit as
// the scene builds them (templates fitted with the scene's room, or the
// scene's garment files), before they are moved to where the motion
// starts. A user's own garment (imported_garment.h) is modelled around
// this body, in these coordinates.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "layers/data/obj.h"
#include "layers/data/skinned_glb.h"
#include "layers/generate/generator_config.h"

namespace layers::generate {

struct TPoseMeshes {
  data::ObjMesh body;
  // The body as a rig (data/skinned_glb.h): bound in its rest pose, with
  // the animation "motion" whose first frame is this T-pose and whose
  // later frames are the scene's motion after the transition (its joints:
  // skin untangling, body.skin_untangle, is not in it). Read back as
  // `body.own` with garment_pose: first_frame, it is this scene's body.
  // Empty (no joints) for a user's mesh sequence, which has no rig.
  data::SkinnedBody rig;
  std::vector<std::pair<std::string, data::ObjMesh>> garments;  // name, mesh with its UVs
  std::string problem;  // why the scene cannot be simulated ("" when it can; garments may then be missing)
};

// Scene `index` of `config` (as `layers generate` would draw it).
TPoseMeshes tpose_meshes(const GeneratorConfig& config, int index);

}  // namespace layers::generate
