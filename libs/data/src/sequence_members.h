// sequence_members.h (private) -- where each array of the schema
// (format.h) lives in memory: the one place that ties the schema's paths
// to the members of BodyStatic, BodyFrames, WindData and GarmentStatic.
// The reader, the writer and the size checks iterate the schema tables and
// reach the data through these; content_hash.cpp keeps its own fixed order
// (changing it would change every recorded hash).
//
// Each function calls f(member) with the member vector of `spec` (a
// std::vector of float, std::int32_t or std::string, const when the
// owner is), or throws layers::Error for a path it does not hold.
#pragma once

#include <string>

#include "layers/core/error.h"
#include "layers/data/format.h"
#include "layers/data/sequence.h"

namespace layers::data {

// body/ arrays that are not per frame.
template <class Body, class F>  // Body: (const) BodyStatic
void with_body_static(Body& b, const ArraySpec& spec, F&& f) {
  const std::string& p = spec.path;
  if (p == "body/faces") return f(b.faces);
  if (p == "body/joint_names") return f(b.joint_names);
  if (p == "body/joint_parents") return f(b.joint_parents);
  if (p == "body/skin_index") return f(b.skin_index);
  if (p == "body/skin_weight") return f(b.skin_weight);
  if (p == "body/tpose_joints") return f(b.tpose_joints);
  throw Error("layers-h5: no static body member for '" + p + "'");
}

// Per-frame body/ and wind/ arrays.
template <class Frames, class Wind, class F>  // (const) BodyFrames, (const) WindData
void with_frames(Frames& b, Wind& w, const ArraySpec& spec, F&& f) {
  const std::string& p = spec.path;
  if (p == "body/positions") return f(b.positions);
  if (p == "body/root") return f(b.root);
  if (p == "body/root_rot") return f(b.root_rot);
  if (p == "body/joints") return f(b.joints);
  if (p == "wind/rotation") return f(w.rotation);
  if (p == "wind/strength") return f(w.strength);
  throw Error("layers-h5: no per-frame member for '" + p + "'");
}

// A garment's arrays that are not per frame (its one per-frame array,
// positions, is GarmentData::positions or one of Window::garments).
template <class Garment, class F>  // (const) GarmentStatic
void with_garment_static(Garment& g, const ArraySpec& spec, F&& f) {
  const std::string& p = spec.path;
  if (p == "faces") return f(g.faces);
  if (p == "rest") return f(g.rest);
  if (p == "uv") return f(g.uv);
  if (p == "uv_faces") return f(g.uv_faces);
  if (p == "panel") return f(g.panel);
  throw Error("layers-h5: no static garment member for '" + p + "'");
}

// Any body/ or wind/ array of a whole sequence.
template <class Seq, class F>  // (const) SequenceData
void with_sequence_array(Seq& seq, const ArraySpec& spec, F&& f) {
  if (spec.per_frame())
    with_frames(seq.body, seq.wind, spec, f);
  else
    with_body_static(seq.body, spec, f);
}

// Any array of a garment of a whole sequence.
template <class Garment, class F>  // (const) GarmentData
void with_garment_array(Garment& g, const ArraySpec& spec, F&& f) {
  if (spec.per_frame()) {
    if (spec.path != "positions") throw Error("layers-h5: no per-frame garment member for '" + spec.path + "'");
    return f(g.positions);
  }
  with_garment_static(g, spec, f);
}

}  // namespace layers::data
