// layers/generate/outfit.h -- the garments of a scene, fitted around the
// body in its T-pose (layers::scene garment templates), as LAYERS-H5
// garment arrays.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/data/sequence.h"
#include "layers/garment/garment.h"
#include "layers/generate/scene_spec.h"

namespace layers::generate {

// One garment per spec.garments entry (the templates' order: inner ones
// first, a bottom before the t-shirt over it, then the outer one), with
// rest shape, faces, UVs, panels, type, layer and attributes filled in
// and no positions yet. The outer garment is fitted over the inner ones.
// `body`: the scene's body in its T-pose (garment::t_pose_body). `room`:
// what the scene's motion asks of the garments (garment_leg_room.h).
std::vector<data::GarmentData> fit_outfit(const garment::TPoseBody& body, const SceneSpec& spec,
                                          const garment::GarmentParams& params,
                                          const garment::MotionRoom* room = nullptr);

// A garment's attributes as stored in LAYERS-H5 (name -> value) and back;
// InputError naming `what` for a missing attribute.
std::map<std::string, double> attribute_map(const sim::GarmentAttributes& attributes);
sim::GarmentAttributes garment_attributes(const std::map<std::string, double>& values, const std::string& what);

}  // namespace layers::generate
