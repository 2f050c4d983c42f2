// layers/generate/scene_spec.h -- what one scene of a dataset is, drawn
// deterministically from the dataset seed and the scene's index: body
// shape, motion (with body.variation: its drawn parameters, see
// motion_variation.h), outfit with per-garment attributes, wind schedule,
// the split it belongs to and its subset tags (T, T+W, L, L+W).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "layers/body/body_model.h"
#include "layers/generate/generator_config.h"
#include "layers/sim/material.h"
#include "layers/sim/wind.h"

namespace layers::generate {

struct GarmentSpec {
  std::string type;                   // a template's type, or "imported" for a user's mesh
  int layer = 0;                      // 0 inner, 1 outer
  sim::GarmentAttributes attributes;  // drawn; an imported garment's side file overrides those it gives
  std::string source;                 // "imported": the outfit's file:<mesh> entry
};

struct SceneSpec {
  int index = 0;
  std::string id;          // "seq-000042"
  std::uint64_t seed = 0;  // the scene's own seed (motion, garment sizes)
  body::ShapeParams shape;
  std::string motion;                 // the exact motion spec (with body.variation: its drawn parameters)
  std::string motion_entry;           // the body.motions entry it was drawn from
  std::vector<GarmentSpec> garments;  // inner garments first, then the outer one
  std::string wind_regime;            // calm, strong or mixed
  std::vector<sim::WindSpan> wind;    // over the recorded frames [0, frames)
  std::string split;                  // train, val or test; empty when held out
  std::vector<std::string> tags;      // subsets: T, T+W, L, L+W, unseen_motion, unseen_garment (or none)
};

// Scene `index` (0-based) of the dataset `config` describes. A scene with a
// held-out motion or outfit (config.splits.unseen_*) has no split and the
// tag unseen_motion / unseen_garment.
SceneSpec sample_scene(const GeneratorConfig& config, int index);

// The split of every scene: a seeded permutation of the indices, the first
// round(test * n) are test, the next round(val * n) val, the rest train.
std::vector<std::string> assign_splits(const GeneratorConfig& config);

// The paper's subsets (its Table 2; docs/format.md "splits.yaml"): a
// jumpsuit (tight) or a dress (loose) under a jacket, with all wind <= 50
// (T, L) or all > 250 (T+W, L+W).
std::vector<std::string> subset_tags(const std::vector<GarmentSpec>& garments, const std::vector<sim::WindSpan>& wind);

// The subsets of held-out scenes (config.splits.unseen_*), and whether a
// scene's tags hold one of them: such a scene has no train/val/test split.
inline constexpr const char* kUnseenMotion = "unseen_motion";
inline constexpr const char* kUnseenGarment = "unseen_garment";
bool is_held_out(const std::vector<std::string>& tags);

std::string scene_id(int index);

}  // namespace layers::generate
