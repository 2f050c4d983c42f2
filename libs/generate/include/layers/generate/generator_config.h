// layers/generate/generator_config.h -- the typed config of `layers
// generate` (configs/data/*.yaml): how many scenes, how long, which bodies,
// motions, outfits, attribute ranges, wind regimes, splits, and the solver.
#pragma once

#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "layers/core/config.h"
#include "layers/data/format.h"
#include "layers/garment/garment.h"
#include "layers/generate/motion_variation.h"
#include "layers/motion/body_config.h"
#include "layers/sim/config.h"
#include "layers/sim/material.h"

namespace layers::generate {

// One outfit: inner garment types (a t-shirt goes with pants or a skirt)
// under one outer garment type.
struct OutfitConfig {
  std::vector<std::string> inner{"jumpsuit"};
  std::string outer = "jacket";
  double weight = 1.0;  // relative sampling weight

  template <class V>
  void visit(V& v) {
    // The types of each layer come from the garment-type table
    // (data/format.h); `file:<mesh>` is a user's own garment
    // (import/garment_file.h). check() checks both.
    static const std::string outer_help = [] {
      std::string h = "outer garment type:";
      for (const std::string& t : data::garment_types_of_layer(1)) h += " " + t;
      return h + ", none, or file:<mesh>";
    }();
    static const std::string inner_help = [] {
      std::string h = "inner garment types:";
      for (const std::string& t : data::garment_types_of_layer(0)) h += " " + t;
      return h + ", or file:<mesh> entries";
    }();
    v("inner", inner, cfg::opt().help(inner_help));
    v("outer", outer, cfg::opt().help(outer_help));
    v("weight", weight, cfg::opt().min(0).help("relative sampling weight"));
  }
};

// A range [lo, hi] for each of the paper's garment attributes.
struct AttributeRanges {
  std::vector<double> mass{0.2, 0.8};
  std::vector<double> stiffness{15, 100};  // tension, compression, shear (drawn separately)
  std::vector<double> bending{15, 200};
  std::vector<double> friction{40, 80};  // friction and self-friction (drawn separately)

  template <class V>
  void visit(V& v) {
    v("mass", mass, cfg::opt().min(0.001).help("[lo, hi]"));
    v("stiffness", stiffness, cfg::opt().min(0).help("[lo, hi] for tension, compression and shear"));
    v("bending", bending, cfg::opt().min(0).help("[lo, hi]"));
    v("friction", friction, cfg::opt().range(0, 80).help("[lo, hi] for friction and self-friction"));
  }
};

// Wind: each scene draws a regime (calm, strong or mixed by the weights),
// then cuts its frames into spans of span_frames [lo, hi] frames, each with
// a random horizontal-ish direction and a strength drawn from the regime's
// range (Blender units).
struct WindConfig {
  double calm_weight = 1, strong_weight = 1, mixed_weight = 1;
  std::vector<double> calm{0, 50};
  std::vector<double> strong{250, 400};
  std::vector<double> mixed{0, 400};
  std::vector<int> span_frames{20, 60};
  double max_elevation_deg = 20;  // wind direction within this angle of horizontal

  template <class V>
  void visit(V& v) {
    v("calm_weight", calm_weight, cfg::opt().min(0));
    v("strong_weight", strong_weight, cfg::opt().min(0));
    v("mixed_weight", mixed_weight, cfg::opt().min(0));
    v("calm", calm, cfg::opt().range(0, 400).help("[lo, hi] strength of calm scenes (<= 50: the T and L subsets)"));
    v("strong", strong, cfg::opt().range(0, 400).help("[lo, hi] strength of windy scenes (> 250: T+W and L+W)"));
    v("mixed", mixed, cfg::opt().range(0, 400).help("[lo, hi] strength of mixed scenes"));
    v("span_frames", span_frames, cfg::opt().min(1).help("[lo, hi] frames per wind span"));
    v("max_elevation_deg", max_elevation_deg, cfg::opt().range(0, 90));
  }
};

// A user's own body in place of ours in every scene (generate/own_body.h,
// import/body_import.h). Its motions are `animation` (the file's own) or,
// for a rigged body, BVH clips retargeted onto its skeleton.
struct OwnBodyConfig {
  std::string file;       // rigged glTF/GLB, FBX, Collada, ...; a .pc2 cache; or a folder of OBJ frames
  std::string mesh;       // a .pc2's faces and rest pose (OBJ); a folder's rest pose (default: its first frame)
  double scale = 1.0;     // the files' units to metres
  std::string animation;  // a rigged file's animation by name ("" = its first)
  std::string garment_pose = "bind";  // rigged: the pose the garments are made around: bind, or first_frame
  std::string hash;                   // recorded by the generator: the content hash of the files

  template <class V>
  void visit(V& v) {
    v("file", file, cfg::opt().help("rigged glTF/GLB, FBX or Collada, a .pc2 vertex cache, or a folder of OBJ frames"));
    v("mesh", mesh, cfg::opt().help("OBJ with the faces and rest pose of a .pc2 (required) or an OBJ folder"));
    v("scale", scale, cfg::opt().range(1e-6, 1e6).help("the files' units to metres"));
    v("animation", animation, cfg::opt().help("the rigged file's animation to play, by name (default: the first)"));
    v("garment_pose", garment_pose,
      cfg::opt()
          .choices({"bind", "first_frame"})
          .help("a rigged body's pose the garments are made around: its bind pose, or the animation's first frame "
                "(the motion then plays from the second)"));
    v("hash", hash, cfg::opt().help("recorded by the generator: content hash of the body's files"));
  }
};

// The motion entry that plays an own body's file animation.
inline constexpr const char* kOwnAnimation = "animation";

struct BodySampling {
  std::optional<OwnBodyConfig> own;  // a user's body instead of ours; absent: ours
  motion::ShapeSampling shape;
  std::vector<std::string> motions{"procedural:walk"};  // drawn uniformly per scene
  std::optional<MotionVariation> variation;             // parametric families (motion_variation.h); absent: off
  int transition_frames = 10;                           // T-pose -> motion blend (part of warm-up)
  double intersection_tolerance_mm = 4.0;
  double self_gap_mm = 0.0;    // room body parts keep from each other (body::IntersectionOptions::gap); 0 = off
  double arm_room_mm = 0.0;    // room for the cloth under the arms (motion::SequenceOptions::arm_room); 0 = off
  double thigh_room_mm = 0.0;  // room for the cloth between the thighs (SequenceOptions::thigh_room); 0 = off
  motion::SkinUntangleConfig skin_untangle;  // smoothing of the skin's own folds (body::SkinUntangler); off by default

  template <class V>
  void visit(V& v) {
    v("own", own, cfg::opt().help("a user's own body (file, mesh, scale, animation) in place of ours"));
    v("shape", shape);
    v("motions", motions,
      cfg::opt().help("motion specs: procedural:<kind>, bvh:<path> or a .bvh file; with body.own: animation or bvh"));
    v("variation", variation, cfg::opt().help("per-scene motion parameters (speed, amplitude, phase, ...)"));
    v("transition_frames", transition_frames,
      cfg::opt().range(1, 300).help("frames blending from the T-pose into the motion"));
    v("intersection_tolerance_mm", intersection_tolerance_mm, cfg::opt().range(0.5, 50));
    v("self_gap_mm", self_gap_mm, motion::kSelfGapOption);
    v("arm_room_mm", arm_room_mm,
      cfg::opt().range(0, 100).help("room for the cloth between arms and torso; closer arms are abducted (0 = off)"));
    v("thigh_room_mm", thigh_room_mm,
      cfg::opt().range(0, 100).help("room for the cloth between the thighs; closer legs are abducted (0 = off)"));
    v("skin_untangle", skin_untangle);
  }
};

struct GarmentSampling {
  garment::GarmentParams fit;  // templates: edge length, ease, lengths, clearances
  std::vector<OutfitConfig> outfits{OutfitConfig{}};
  AttributeRanges attributes;
  // How the drawn attributes become physical parameters (docs/sim.md
  // section 3); the defaults are those of every shipped dataset.
  sim::MaterialMapping material;
  // Skirts and dresses (torso sections below the hips) at least as loose as
  // the scene's motion spreads the legs (garment_leg_room.h).
  bool leg_room = true;
  // Pants and jumpsuits (their sections from the waist to mid-thigh) at
  // least as loose as the skin's growth there in the scene's motion asks.
  // Off unless a config asks for it, so that datasets made before it
  // existed keep their config (same_saved_config); the shipped configs
  // other than `small` turn it on.
  bool hip_room = false;
  // Set by resolve_garment_files (imported_garment.h), never by hand: the
  // content hash of every garment file and side file the outfits name, so
  // that a dataset folder is not resumed with other garments.
  std::map<std::string, std::string> files;

  template <class V>
  void visit(V& v) {
    v("fit", fit);
    v("outfits", outfits);
    v("attributes", attributes);
    v("material", material);
    v("leg_room", leg_room,
      cfg::opt().help("make skirts and dresses loose enough for the legs' widest spread in the scene's motion"));
    v("hip_room", hip_room,
      cfg::opt().help(
          "make pants and jumpsuits loose enough at the seat and thighs for the skin's growth in the scene's motion"));
    v("files", files,
      cfg::opt().help("recorded by the generator: content hash of each garment file (file:<mesh>) and side file"));
  }
};

// The label of an outfit in configs and reports: inner types joined by
// '+', then '/' and the outer type, e.g. "tshirt+skirt/jacket_hood".
std::string outfit_label(const OutfitConfig& outfit);

// Held-out scenes (generalisation studies): a scene whose motion is in
// `unseen_motions` or whose outfit is in `unseen_outfits` is in none of
// train/val/test but in the subset `unseen_motion` / `unseen_garment` of
// splits.yaml, so no model trains or validates on it.
struct SplitConfig {
  double val = 0.1;                         // share of scenes in val
  double test = 0.1;                        // share in test; the rest is train
  std::vector<std::string> unseen_motions;  // entries of body.motions
  std::vector<std::string> unseen_outfits;  // outfit labels (outfit_label)

  template <class V>
  void visit(V& v) {
    v("val", val, cfg::opt().range(0, 1));
    v("test", test, cfg::opt().range(0, 1));
    v("unseen_motions", unseen_motions, cfg::opt().help("motions held out of train/val/test (subset unseen_motion)"));
    v("unseen_outfits", unseen_outfits,
      cfg::opt().help("outfits held out of train/val/test, as inner+inner/outer (subset unseen_garment)"));
  }
};

struct GeneratorConfig {
  std::string name = "layers";
  std::uint64_t seed = 0;
  int sequences = 6;
  int frames = 30;        // recorded frames per sequence
  int drape_frames = 30;  // T-pose frames simulated before the transition (not recorded)
  // Clean windows (docs/sim.md): a scene whose recorded frame k breaks a
  // per-frame rule of sim.validation (sim::frame_violations) stops there
  // and keeps frames 0..k-1 as a shorter sequence when k is at least
  // this. 0: off, the whole scene or nothing (as before the setting).
  int window_min_frames = 0;
  int sequences_per_shard = 16;
  BodySampling body;
  GarmentSampling garments;
  WindConfig wind;
  SplitConfig splits;
  sim::SolverConfig sim;

  template <class V>
  void visit(V& v) {
    v("name", name, cfg::opt().help("dataset name"));
    v("seed", seed, cfg::opt().help("seed of the whole dataset; scene i uses a seed derived from it"));
    v("sequences", sequences, cfg::opt().range(1, 10000000));
    v("frames", frames, cfg::opt().range(3, 100000).help("recorded frames per sequence (30 fps)"));
    v("drape_frames", drape_frames, cfg::opt().range(1, 10000).help("T-pose settling frames before recording"));
    v("window_min_frames", window_min_frames,
      cfg::opt().range(0, 100000).help(
          "clean windows: a scene whose recorded frame k breaks a per-frame rule of sim.validation keeps its frames "
          "before k when k is at least this (3 to frames); 0: the whole scene or nothing"));
    v("sequences_per_shard", sequences_per_shard, cfg::opt().range(1, 100000));
    v("body", body);
    v("garments", garments);
    v("wind", wind);
    v("splits", splits);
    v("sim", sim);
  }
};

// Whether the generator config saved at `path` (a dataset folder's
// generator.yaml) is `resolved` (cfg::to_yaml of a resolved config). The
// saved file is read through the schema first, so a setting added later
// whose default keeps the old behaviour does not set apart the folders
// made before it existed; a file the schema rejects is not the same.
bool same_saved_config(const std::string& path, const std::string& resolved);

// The body.motions entries that name a folder of clips (a motion library,
// motion::clip_folder_entries) replaced by its clips in name order, so
// that scenes draw a clip uniformly and the saved config lists the clips
// a dataset was made from. Not for an own body's entries.
void expand_motion_folders(GeneratorConfig& config, const std::string& file);

// A generator config as every verb reads one: the file, its `--set`
// overrides in order, the typed config, motion folders expanded, check(),
// and the garment files its outfits name read and recorded
// (resolve_garment_files, imported_garment.h). An empty outfit list (the
// body alone) is refused when the config is `to_simulate`. InputError
// naming the file on any problem.
GeneratorConfig load_generator_config(const std::string& file, const std::vector<std::string>& sets,
                                      bool to_simulate = true);

// The generator config a dataset's manifest records (dataset.yaml's
// `generator`), read through the schema; nullopt for a dataset not made by
// `layers generate`. InputError naming `file` when it does not read.
std::optional<GeneratorConfig> recorded_generator_config(const std::string& generator_yaml, const std::string& file);

// Cross-field checks the per-field ranges cannot express (ranges are
// [lo, hi] pairs, weights not all zero, known garment types, outfits with
// at least one inner garment, val + test < 1). InputError naming `file`
// and the key path.
void check(const GeneratorConfig& config, const std::string& file);

}  // namespace layers::generate
