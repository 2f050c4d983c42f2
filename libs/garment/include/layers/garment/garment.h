// layers/garment/garment.h -- garment templates: sewing-pattern garments fitted
// to a shaped body in its T-pose.
//
// Types (docs/format.md): outer layer `jacket`, `jacket_hood`; inner
// layer `dress`, `dress_belt`, `jumpsuit`, `tshirt`, `pants`, `skirt`. Each
// garment is a set of flat panels (bodice, sleeves, skirt, legs, belt,
// hood) whose coordinates in metres are the UVs, one chart per panel,
// meshed at a target edge length, wrapped around the body's cross-sections
// (plus ease) and sewn into one connected, outward-oriented mesh; openings
// (neckline, hems, cuffs, waist, face) stay open. Sizes, lengths and
// looseness are drawn per seed from GarmentParams. An outer garment is
// fitted over the garments under it (their vertices join the envelope it
// is measured on) with a clearance. After sewing, vertices are pushed out
// of the body (and of the garments under them) by the nearest-vertex test
// (docs/metrics.md), so a rest pose has zero H- and L-penetration.
// For the layer test only outer vertices within `layer_reach` of the inner
// layer count: far from it the nearest inner vertex is often on an open
// edge whose normal says little (a jacket sleeve over a bare forearm finds
// the armhole of a sleeveless dress), and pushing those would only deform
// a garment that is already outside (it is built around the inner one).
//
// Rest shape: `vertices` are the placed 3D positions and are also the rest
// shape (edge rest lengths come from them), not the flat panel lengths;
// the flat lengths are the UVs, flattened from the placed panels as
// rigidly as possible, so they differ from the 3D ones only by a few
// percent (more where a panel curves both ways: shoulders, hood).
//
// Outfits: the inner layer is one garment, or a t-shirt over pants or a
// skirt (two layer-0 garments, stored separately; the bottom is built first
// and the t-shirt over it, its hem covering the waistband). The outer
// layer (optional) is a jacket or a jacket with hood.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/core/config.h"
#include "layers/garment/garment_body.h"
#include "layers/garment/garment_pattern.h"
#include "layers/garment/garment_pieces.h"
#include "layers/geometry/penetration.h"

namespace layers::garment {

// Garment generation settings. Ranges are [lo, hi] in metres unless noted;
// each garment draws its values uniformly from them.
struct GarmentParams {
  double edge_length = 0.02;      // target edge length
  double body_clearance = 0.006;  // rest pose: every vertex this far in front of the skin
  double layer_gap = 0.004;       // rest pose: every vertex this far in front of the garments under it
  double layer_reach = 0.06;      // ... counting only vertices this close to them (see below)
  std::vector<double> layer_clearance{0.015, 0.03};  // ease of an outer garment over what it covers
  std::vector<double> ease_fitted{0.008, 0.02};      // jumpsuit, dress bodice, skirt waist
  std::vector<double> ease_loose{0.02, 0.045};       // t-shirt
  std::vector<double> ease_pants{0.012, 0.03};
  std::vector<double> flare{0.05, 0.35};         // extra ease per metre below the hips (skirts, dresses)
  std::vector<double> top_length{0.3, 1.0};      // t-shirt hem: 0 = natural waist, 1 = crotch
  std::vector<double> jacket_length{0.8, 1.3};   // same scale
  std::vector<double> skirt_length{0.15, 0.65};  // hem: 0 = crotch, 1 = ankle
  std::vector<double> dress_length{0.2, 0.75};   // same scale
  std::vector<double> pants_length{0.7, 1.0};    // same scale
  std::vector<double> sleeve_short{0.2, 0.45};   // share of armhole -> wrist
  std::vector<double> sleeve_long{0.85, 1.0};
  double long_sleeves = 0.5;  // chance of long sleeves (t-shirt, jumpsuit)
  double sleeveless = 0.4;    // chance of no sleeves (dress, jumpsuit)
  std::vector<double> belt_width{0.03, 0.06};
  std::vector<double> hood_ease{0.03, 0.06};

  template <class V>
  void visit(V& v) {
    v("edge_length", edge_length, cfg::opt().range(0.004, 0.1).help("target edge length (m)"));
    v("body_clearance", body_clearance, cfg::opt().range(0, 0.05).help("rest-pose gap to the skin (m)"));
    v("layer_gap", layer_gap, cfg::opt().range(0, 0.05).help("rest-pose gap to the garments underneath (m)"));
    v("layer_reach", layer_reach,
      cfg::opt().range(0.01, 1).help("outer vertices farther than this from the inner layer are not pushed (m)"));
    v("layer_clearance", layer_clearance, cfg::opt().range(0.005, 0.1).help("outer over inner ease [lo, hi] (m)"));
    v("ease_fitted", ease_fitted, cfg::opt().range(0.003, 0.1).help("[lo, hi] (m)"));
    v("ease_loose", ease_loose, cfg::opt().range(0.003, 0.15).help("[lo, hi] (m)"));
    v("ease_pants", ease_pants, cfg::opt().range(0.003, 0.1).help("[lo, hi] (m)"));
    v("flare", flare, cfg::opt().range(0, 1).help("[lo, hi] extra ease per metre below the hips"));
    v("top_length", top_length, cfg::opt().range(0, 1.5).help("[lo, hi] 0 = waist, 1 = crotch"));
    v("jacket_length", jacket_length, cfg::opt().range(0, 1.6).help("[lo, hi] 0 = waist, 1 = crotch"));
    v("skirt_length", skirt_length, cfg::opt().range(0.05, 1).help("[lo, hi] 0 = crotch, 1 = ankle"));
    v("dress_length", dress_length, cfg::opt().range(0.05, 1).help("[lo, hi] 0 = crotch, 1 = ankle"));
    v("pants_length", pants_length, cfg::opt().range(0.2, 1).help("[lo, hi] 0 = crotch, 1 = ankle"));
    v("sleeve_short", sleeve_short, cfg::opt().range(0.05, 1).help("[lo, hi] share of armhole to wrist"));
    v("sleeve_long", sleeve_long, cfg::opt().range(0.05, 1).help("[lo, hi] share of armhole to wrist"));
    v("long_sleeves", long_sleeves, cfg::opt().range(0, 1).help("chance of long sleeves"));
    v("sleeveless", sleeveless, cfg::opt().range(0, 1).help("chance of no sleeves (dress, jumpsuit)"));
    v("belt_width", belt_width, cfg::opt().range(0.01, 0.2).help("[lo, hi] (m)"));
    v("hood_ease", hood_ease, cfg::opt().range(0.005, 0.15).help("[lo, hi] (m)"));
  }
};

// Throws InputError when a range is not two numbers lo <= hi, or the edge
// length is outside [0.004, 0.1] m.
void validate(const GarmentParams& params);

// The names of layers::data's garment-type table (data/format.h) that
// have a template (all but `imported`), and a type's layer there
// (InputError for an unknown type or one without a template).
const std::vector<std::string>& garment_types();
int garment_layer(const std::string& type);

// Builds one garment around `body`, over the garments in `under` (their
// vertices are enclosed with the layer clearance). With `room`, its torso
// sections (skirts, dresses) and pants sections (pants, jumpsuits) are at
// least that loose per height (garment_leg_room.h).
// Deterministic for a seed.
GarmentMesh build_garment(const std::string& type, const TPoseBody& body, const GarmentParams& params,
                          std::uint64_t seed, const std::vector<const GarmentMesh*>& under = {},
                          const MotionRoom* room = nullptr);
GarmentMesh build_garment(const std::string& type, const body::Body& body, const GarmentParams& params,
                          std::uint64_t seed);

// An outfit: `inner` is one type, or "tshirt" with "pants" or "skirt";
// `outer` is "jacket", "jacket_hood" or "" (none). Returns the inner
// garments (bottom first) then the outer one, each with its layer set.
// `room` as for build_garment, for every garment of the outfit.
std::vector<GarmentMesh> build_outfit(const std::vector<std::string>& inner, const std::string& outer,
                                      const TPoseBody& body, const GarmentParams& params, std::uint64_t seed,
                                      const MotionRoom* room = nullptr);

// Rest-pose contact of a garment: vertices behind (< 0) or closer than
// `clearance` to a surface, by the nearest-vertex test, among the vertices
// within `reach` of the surface.
struct ContactCount {
  int behind = 0, too_close = 0;
  double min_offset = 0;
};
ContactCount count_contact(const geometry::Points& vertices, const geometry::Surface& surface, double clearance,
                           double reach = std::numeric_limits<double>::infinity());

}  // namespace layers::garment
