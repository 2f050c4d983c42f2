// layers/motion/asf_amc.h -- Acclaim ASF/AMC motion capture, the CMU
// database's original format, read into the same clip as a BVH file
// (bvh.h), so retargeting, resampling, windows and mirroring treat both
// alike.
//
// The skeleton (.asf): units, the root (order of its AMC values, axis
// order, orientation), bones (direction and length at rest, the axis
// angles of the bone's own frame C with their order, the AMC degrees of
// freedom among rx, ry, rz) and the hierarchy. The motion (.amc): per
// frame, a frame number, then per bone its values in its dof order.
// A bone's rotation relative to its parent is C * M * C^-1, M the dof
// rotations applied in the order listed (CMU: rx, then ry, then rz), C
// the axis angles applied in the axis order (XYZ: x first); the root's
// rotation likewise with its orientation, its translation from its TX TY
// TZ values. Each bone becomes a joint at the bone's start (its parent
// bone's end) turning the bone; a leaf's end is an End Site. Lengths are
// read as the CMU database writes them, inches times `:units length`, and
// given in metres (x 0.0254 / length). Angles are degrees unless
// `:units angle rad`. The frame rate is not in the files: 120 fps, the
// CMU capture rate, unless given.
//
// Malformed files raise InputError naming the file and line; the bounds
// of BVH clips apply (joints, frames, joints x frames, duration).
#pragma once

#include <string>

#include "layers/motion/bvh.h"

namespace layers::motion {

inline constexpr double kCmuFramesPerSecond = 120.0;

// The skeleton of an AMC file: `<folder>/<subject>.asf` for a CMU name
// `<subject>_<trial>.amc`, else the only .asf beside it (InputError when
// there is none or several).
std::string asf_for_amc(const std::string& amc_path);

// `asf_path` "" takes asf_for_amc(amc_path).
BvhClip read_asf_amc(const std::string& amc_path, const std::string& asf_path = "", double fps = kCmuFramesPerSecond);

// A motion clip by its extension: .bvh (read_bvh) or .amc (read_asf_amc).
BvhClip read_clip(const std::string& path);
bool is_clip_file(const std::string& path);

}  // namespace layers::motion
