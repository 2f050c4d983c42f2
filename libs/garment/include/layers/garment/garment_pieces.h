// layers/garment/garment_pieces.h -- the pieces garments are assembled from,
// each adding placed panel grids and seams to a Pattern:
//   tube   front + back panels on horizontal sections (skirt, belt, bodice rows)
//   top    a bodice (tube rows up to the armpit, then shoulder columns up
//          to the shoulder seam and neckline), optional sleeves, optional
//          zipped centre front
//   pants  four panels (front/back x left/right) with a crotch
//   hood   two panels sewn to a neckline
// Pieces join along "quarters": the four edges of a waist or neck line
// running from the centre (front or back) to the side, so that a bodice
// hem can be sewn to a skirt or pants waist quarter by quarter.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "layers/garment/garment_body.h"
#include "layers/garment/garment_pattern.h"

namespace layers::garment {

// Front-left (+x), front-right, back-left, back-right; each from the
// centre line to the side (or the shoulder, for a neckline).
struct Quarters {
  Edge fl, fr, bl, br;
  std::vector<Edge> all() const { return {fl, fr, bl, br}; }
};
void sew_quarters(Pattern& pattern, const Quarters& a, const Quarters& b);
void open_quarters(Pattern& pattern, const Quarters& q);
// The grid points of an edge, from its `from` end to its `to` end.
std::vector<body::Vec3> edge_points(const Pattern& pattern, const Edge& e);

// Ease (m), or any setting that varies with height, as a piecewise-linear
// function of height, constant beyond its first and last knots.
struct EaseProfile {
  std::vector<std::pair<double, double>> knots;  // (y, ease), ascending y
  EaseProfile() = default;
  explicit EaseProfile(double constant) : knots{{0.0, constant}} {}
  EaseProfile& at(double y, double ease);  // adds a knot
  double operator()(double y) const;       // throws layers::Error without knots
  bool empty() const { return knots.empty(); }
};

// The room a scene's motion asks of the garments (garment_leg_room.h); an
// empty profile asks for none.
struct MotionRoom {
  EaseProfile legs;  // least ease of torso sections per height (skirts, dresses: the legs' spread)
  EaseProfile hips;  // least ease of pants sections per height (pants, jumpsuits: the skin's growth at the seat)
};

struct FitContext {
  const Envelope& env;
  const Landmarks& marks;
  double step;                       // spacing of grid rows and columns (m)
  const MotionRoom* room = nullptr;  // what the scene's motion asks for (garment_leg_room.h)
};

// Parts that torso sections enclose (no arms, hands, head, neck or feet).
constexpr PartMask kTorsoParts = kAllParts & ~(kArms | kHands | kHeadNeck | kFeet);

// Front and back panels between heights y0 < y1.
struct TubeQuarters {
  Quarters bottom, top;
};
// `hang` (per metre, as a function of height) lets loose cloth fall from
// bulges above (SectionSpec::hang); pieces sewn together share both profiles.
TubeQuarters build_tube(Pattern& pattern, const FitContext& ctx, const std::string& name, double y0, double y1,
                        const EaseProfile& ease, const EaseProfile& hang);

struct TopSpec {
  double hem = 0;              // height of the bottom row
  EaseProfile ease;            // of the torso rows (up to the armpit)
  EaseProfile hang{0.0};       // of the torso rows (see build_tube)
  double armhole_drop = 0.02;  // armpit of the garment below the body's
  // Neckline: where the shoulders meet a vertical elliptic cylinder round
  // the neck, wider than the neck by neck_extra and reaching neck_front
  // (neck_back) further forward (backward) for a scoop.
  double neck_extra = 0.015;
  double neck_front = 0.03, neck_back = 0.01;
  double shoulder_ease = 0.012;  // over the shoulders and at the armhole (the garment rests there)
  double sleeve_ease = 0.02;     // around the arm, away from the armhole
  double sleeve = 0;             // 0: sleeveless; else length as a share of armhole -> wrist
  bool split_front = false;      // two front panels sewn at the centre (zipped jacket)
};
struct TopQuarters {
  Quarters hem, neck;
};
TopQuarters build_top(Pattern& pattern, const FitContext& ctx, const TopSpec& spec);

struct PantsSpec {
  double waist = 1.0, hem = 0.1;
  EaseProfile ease;
};
// Returns the waist quarters.
Quarters build_pants(Pattern& pattern, const FitContext& ctx, const PantsSpec& spec);

struct HoodSpec {
  double ease = 0.04;     // around the head
  double opening = 0.25;  // how far round the face opening reaches: 0 = 52, 1 = 80 degrees from the front
};
void build_hood(Pattern& pattern, const FitContext& ctx, const Quarters& neck, const HoodSpec& spec);

}  // namespace layers::garment
