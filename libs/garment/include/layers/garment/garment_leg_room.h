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
//
// Hip room: pants and jumpsuits have a tube per leg, and what they meet is
// the skin growing rather than the legs spreading. A kick that raises the
// knee to hip height stretches the skin of the seat and the hip creases by
// a third (its area, band by band), where fitted cloth gives only its
// strain cap in each direction; the cloth is then drawn into the body.
// Per height from the natural waist to mid-thigh, the skin's area in a 4 cm
// band is followed through the motion; a band asks for the extra outline
// its area needs beyond what capped cloth covers: its T-pose outline times
// (largest area ratio / (1 + cap)^2 - 1), plus kLegRoomMargin of it, over
// 2 pi. Cloth slides between neighbouring bands, so the whole region gets
// the most any band asks for. The pants template gives its sections that ease (never so
// much that a leg crosses the midline below the crotch, and tapering to
// none at the waistband), and keeps its crotch where its own ease puts it.
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

// `frames` as for leg_room; `max_strain` is the cloth's strain cap (0.08:
// 8%). Returns the minimum ease (m) of pants sections per height: one
// value at knots every 2 cm from the natural waist to halfway between
// crotch and knee (0 where the skin never grows by more than the cap
// allows), and 0 from 2 cm beyond them.
EaseProfile hip_room(const TPoseBody& body, const std::vector<geometry::Points>& frames, double max_strain);

}  // namespace layers::garment
