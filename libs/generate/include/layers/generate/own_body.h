// layers/generate/own_body.h -- a user's own body (config `body.own`,
// docs/own-data.md) as the body of every scene: the file read by
// import/body_import.h becomes a body of ours (its rest mesh, skeleton and
// weights; the pose the garments are made around, in place of our
// T-pose, is a rigged body's bind pose or, with garment_pose:
// first_frame, its animation's first frame, and a mesh sequence's rest
// pose) and a body sequence: the file's own
// animation (`animation` in body.motions) or a BVH clip retargeted onto
// its skeleton, blended in from the rest pose over
// body.transition_frames, posed by our skinning; or a mesh sequence's
// frames as they are. The user's motion is taken as it is: no arm or
// thigh room, no repair of self-intersections (a rig's are counted; the
// scene's validation measures the body as ours in either case).
#pragma once

#include <string>

#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"
#include "layers/motion/body_config.h"

namespace layers::generate {

// Checks what body.own asks against the rest of the config (each failure
// one InputError naming `file` and the key): the body file exists; no
// setting that would be ignored (garment_pose or animation on a mesh
// sequence, mesh on a rigged file, body.variation); every motion is
// `animation`, or a BVH clip for a rigged body; every outfit is made of
// garment files (templates are fitted to our body's landmarks).
void check_own_body(const GeneratorConfig& config, const std::string& file);

// Reads the body's files (every check of import_body) and records the
// content hash of what was read (mesh, rig, weights, frames) in
// body.own.hash, so that a dataset is not resumed with another body.
// No-op without body.own.
void resolve_own_body(GeneratorConfig& config);

// The scene's body and motion: config.body.transition_frames from the
// rest pose, then config.frames frames of the motion spec.motion. An
// animation shorter than config.frames, or a skeleton a BVH clip cannot be
// retargeted onto (the joints retargeting needs, soles on both feet), is
// an InputError naming the file. The files are read once per process
// for all scenes of one config (resolve_own_body reads them afresh, for
// their hash).
motion::GeneratedBody own_body(const GeneratorConfig& config, const SceneSpec& spec);

}  // namespace layers::generate
