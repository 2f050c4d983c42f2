// layers/garment/garment_leg_room.h -- the room a scene's motion needs
// between the legs. A skirt or dress is a tube around both legs; when a
// stride, a run or a squat spreads them wider than the cloth can stretch
// around, the legs must pass through it (a knee-length dress whose hem is
// 1.2 m round meets legs whose outline is 1.45 m round at the hem, mid-stride).
// Per height of the T-pose body from the hips down, the outline of the
// skin there (the convex hull, as garment sections measure it) is followed
// through every frame of the motion in the pelvis's frame. The room is the
// ease that lets a torso section at that height go round the widest of
// them: the outline's growth over the T-pose's, plus kLegRoomMargin of it,
// over 2 pi (a hull dilated by e is 2 pi e longer). The templates keep
// their torso sections at least that loose.
#pragma once

#include <vector>

#include "layers/garment/garment_body.h"
#include "layers/garment/garment_pieces.h"
#include "layers/geometry/mesh.h"

namespace layers::garment {

// Share added to the extra outline a motion needs (cloth is not drawn
// tight around a stride).
constexpr double kLegRoomMargin = 0.1;

// `frames`: the skin in every frame of the motion (same vertex order as
// body.mesh), already moved into the T-pose's pelvis frame. Returns the
// minimum ease (m) per height, knots every 2 cm from the hips to just
// above the ankles (0 where the motion never spreads the legs wider than
// the T-pose does), and 0 from 2 cm above the hips up.
EaseProfile leg_room(const TPoseBody& body, const std::vector<geometry::Points>& frames);

}  // namespace layers::garment
