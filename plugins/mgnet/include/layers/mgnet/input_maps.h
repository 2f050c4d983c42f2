// layers/mgnet/input_maps.h -- MGNet's inputs for one step: per-vertex
// features splatted into each garment's UV image, plus constant maps.
//
// Positions are root-relative (p - root of the same frame) and normalised
// with the model's Normalization; v(t) = rel(t) - rel(t-1). Seeds: the body
// vertex nearest to each garment vertex at t (body_seeds.h). Base
// prediction (what the decoded displacement is added to), by Base:
//   constant_velocity  p(t+1) = root(t+1) + rel(t) + v(t): the garment
//                      keeps its root-relative velocity and moves with the
//                      root's known next translation;
//   body_seeds         p(t+1) = p(t) + seed(t+1) - seed(t): each vertex
//                      moves with its seed point (MGNet's own output is
//                      carried by the body seeds).
//
// State encoder, kStateChannels maps:
//   rel(t) (3, position-normalised), rest offset (3, position-scaled),
//   rest normal (3), current normal (3), coverage (1), layer (1, constant).
// Dynamic encoder, kDynamicChannels maps:
//   rel(t-1) (3, position-normalised), v(t) (3, velocity-normalised),
//   acceleration towards the body: seed velocity - v(t) (3, acceleration-
//   scaled), body force: seed position at t+1 - base prediction (3,
//   position-scaled), seed velocity t -> t+1 (3, body-velocity-normalised),
//   coverage (1), and constant maps: wind strength(t+1) / 400 (1), wind
//   direction at t+1 (3: the rotation applied to +z), root velocity t ->
//   t+1 (3, velocity-scaled) and root acceleration (3, acceleration-scaled).
#pragma once

#include <cstdint>
#include <string>

#include <ATen/ATen.h>

#include "layers/mgnet/layout.h"
#include "layers/mgnet/params.h"
#include "layers/zoo/model.h"

namespace layers::mgnet {

inline constexpr std::int64_t kStateChannels = 14;
inline constexpr std::int64_t kDynamicChannels = 26;

// "constant_velocity" or "body_seeds" (Params::base).

struct StepMaps {
  at::Tensor state;    // [G,kStateChannels,R,R]
  at::Tensor dynamic;  // [G,kDynamicChannels,R,R]
  at::Tensor frames;   // [V,3,3] tangent frames (rows t, b, n) at t
  at::Tensor base;     // [V,3] base prediction at t+1, world space
};

// All garments at once (concatenated as in `layout`); the input is already
// checked by Model::step.
StepMaps step_maps(const GarmentLayout& layout, const zoo::StepInput& input, const zoo::Normalization& norm, Base base);

}  // namespace layers::mgnet
