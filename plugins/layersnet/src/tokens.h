// plugins/layersnet/src/tokens.h -- the inputs of LayersNet's abstract tokens:
// garment attributes min-max scaled with the paper's ranges, and the wind
// token's features (present only while the wind blows).
#pragma once

#include <cstdint>

#include <ATen/ATen.h>

#include "frame.h"
#include "layers/zoo/model.h"

namespace layers::layersnet {

// mass, tension, compression, shear, bending, friction, self_friction
// (layers/zoo/model.h order) and their sampling ranges (the paper's; the
// generator's defaults, docs/format.md "Garment attributes").
inline constexpr std::int64_t kAttributes = 7;
inline constexpr double kAttributeLow[kAttributes] = {0.2, 15, 15, 15, 15, 40, 40};
inline constexpr double kAttributeHigh[kAttributes] = {0.8, 100, 100, 100, 200, 80, 80};

// (x - low) / (high - low) over the last dimension ([...,7]).
at::Tensor scale_attributes(const at::Tensor& raw);

// Wind token input: root velocity at t and t+1 and root acceleration at t
// (root-relative quantities' scales: garment velocity / acceleration std),
// wind rotation (w,x,y,z) at t and t+1, strength/400 at t and t+1; vectors
// and rotations in the step's frame of t+1.
inline constexpr std::int64_t kWindFeatures = 19;

// Whether the wind blows at t or t+1 (strength > 0).
bool wind_present(const zoo::StepInput& in);
// [1,19] float on the input's device.
at::Tensor wind_features(const zoo::StepInput& in, const zoo::Normalization& norm, const StepFrames& frames);

}  // namespace layers::layersnet
