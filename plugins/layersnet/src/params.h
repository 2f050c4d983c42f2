// plugins/layersnet/src/params.h -- LayersNet's configuration (the `params` of
// a `model: {name: layersnet}` section), defaults as in the paper scaled to
// metres (docs/layersnet.md explains each choice). Torch-free.
#pragma once

#include <cstdint>
#include <string>

#include "layers/core/config.h"

namespace layers::layersnet {

// The integration base and how it blends with p + v (Params::base, blend).
enum class Base { inertial, body, bones, skin };
inline const cfg::EnumNames<Base>& enum_names(Base) {
  static const cfg::EnumNames<Base> names{
      {Base::inertial, "inertial"}, {Base::body, "body"}, {Base::bones, "bones"}, {Base::skin, "skin"}};
  return names;
}
enum class Blend { radius, learned };
inline const cfg::EnumNames<Blend>& enum_names(Blend) {
  static const cfg::EnumNames<Blend> names{{Blend::radius, "radius"}, {Blend::learned, "learned"}};
  return names;
}

struct Params {
  double patch_size = 0.1;             // UV square side (UVs are sewing-pattern metres)
  double world_radius = 0.06;          // E^W: patch centroids closer than this (m; A.3's 0.6 at 10x scale)
  double body_radius = 0.04;           // body senders / decoder body vertex (m; A.3's 0.4 at 10x scale)
  std::int64_t max_body_senders = 16;  // body vertices per patch, closest first
  std::int64_t width = 128;            // token width (encoders, processor, decoder)
  std::int64_t blocks = 4;             // processor blocks
  std::int64_t heads = 8;              // attention heads: half E^M, half E^W
  bool heading_frame = false;          // positions in the root's heading frame (else world axes)
  // What the predicted acceleration is added to: "inertial" (the paper:
  // p + v), "body" (p + the displacement of the vertex's nearest body
  // vertex from t to t+1 where one lies within body_radius, p + v
  // elsewhere), "bones" (likewise, but p moved by the skeleton bones the
  // vertex is bound to in the rest pose) or "skin" (p moved by the skinning
  // of the body vertex nearest its rest position in the T-pose; both in
  // joint_binding.h).
  Base base = Base::inertial;
  // Where and how much the body or bones base replaces p + v: "radius"
  // (fully, within body_radius of the body) or "learned" (a per-vertex
  // gate g in (0,1) the decoder predicts beside the acceleration:
  // v + g (follow - v); for "bones" and "skin" everywhere, for "body"
  // within body_radius, where a nearest body vertex exists).
  Blend blend = Blend::radius;

  template <class V>
  void visit(V& v) {
    v("patch_size", patch_size, cfg::opt().range(1e-4, 10).help("side of a UV patch square (UV units = m)"));
    v("world_radius", world_radius, cfg::opt().range(0, 10).help("world-edge radius between patch centroids (m)"));
    v("body_radius", body_radius,
      cfg::opt().range(0, 10).help("body vertices this close to a patch centroid are its senders (m)"));
    v("max_body_senders", max_body_senders, cfg::opt().range(0, 1024).help("body senders per patch, closest first"));
    v("width", width, cfg::opt().range(2, 4096).help("token width"));
    v("blocks", blocks, cfg::opt().range(0, 64).help("processor blocks"));
    v("heads", heads, cfg::opt().range(2, 256).help("attention heads (even: half E^M, half E^W; divides width)"));
    v("heading_frame", heading_frame,
      cfg::opt().help("express each step in the body root's heading frame (yaw about +y) instead of world axes"));
    v("base", base,
      cfg::opt().help("integration base within body_radius of the body: p + v (inertial), the nearest body vertex's "
                      "displacement (body), the motion of the vertex's rest-pose bones (bones) or of its T-pose "
                      "nearest body vertex's skinning (skin)"));
    v("blend", blend,
      cfg::opt().help("body/bones/skin base: replaces p + v within body_radius (radius) or blended with it by a "
                      "learned per-vertex gate (learned)"));
  }
};

// Reads and checks the parameters (null: all defaults). Throws InputError
// naming the key (heads odd or not dividing width; blend learned with the
// inertial base, which has nothing to blend).
Params read_params(const cfg::Node& node);

}  // namespace layers::layersnet
