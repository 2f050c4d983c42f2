// layers/data/value_bounds.h -- the physical bounds every frame read from a
// dataset must satisfy, so that damaged or absurd ground truth is an input
// error naming file, sequence, frame and field, never a model's fault:
// every value finite; the body root within kMaxRootDistance of the origin;
// body vertices, joint positions and garment vertices within
// kMaxDistanceFromRoot of the body root of their frame; wind strength in
// [0, kMaxWindStrength] (format.h). Checked by the reader on every frame it returns
// (Dataset::read_frames, read_window, read_sequence) and so by `layers
// validate`.
#pragma once

#include <string>

#include "layers/data/format.h"
#include "layers/data/sequence.h"

namespace layers::data {

inline constexpr double kMaxDistanceFromRoot = 10.0;  // m
inline constexpr double kMaxRootDistance = 1.0e4;     // m

// Throws InputError(file, "/seq/<id>/<array>", expected, got) for the first
// value out of bounds, with the frame (of the sequence) and the vertex or
// joint. `window` holds frames first .. first + count - 1 of sequence `info`.
void check_frame_values(const Window& window, std::int64_t first, std::int64_t count, const SequenceInfo& info,
                        const std::string& file);

}  // namespace layers::data
