// garment_recipes.cpp -- what each garment type is made of (pieces and
// seams between them) and how its sizes are drawn: heights come from the
// body's landmarks (waist, hips, crotch, ankle), eases and lengths from the
// GarmentParams ranges.
#include "layers/garment/garment_recipes.h"

#include <algorithm>

#include "layers/core/error.h"

namespace layers::garment {
namespace {

double draw(Rng& rng, Style& style, const char* key, const std::vector<double>& range) {
  const double v = rng.range(range);
  style.emplace_back(key, v);
  return v;
}

double draw(Rng& rng, Style& style, const char* key, double lo, double hi) { return draw(rng, style, key, {lo, hi}); }

// Hem height for a length share between the crotch (0) and the ankle (1).
double leg_hem(const Landmarks& m, double share, double above_ankle) {
  return m.crotch - share * (m.crotch - m.ankle - above_ankle);
}

// A waistband between just above the hip joints (low rise) and the natural waist.
double low_waist(const Landmarks& m, Rng& rng, Style& style) {
  const double rise = draw(rng, style, "rise", 0.3, 1.0);
  const double low = m.hip_joint + 0.06;
  return low + rise * std::max(0.0, m.waist - low);
}

// Loose cloth falls from a bulge at about 17 degrees from vertical.
constexpr double kHang = 0.3;

// Ease over the shoulders: a garment rests there, so at most ~1.2 cm.
double snug(const GarmentParams& p, double ease) { return std::max(p.body_clearance + 0.004, std::min(ease, 0.012)); }

double sleeves(const GarmentParams& p, Rng& rng, Style& style, double p_none, double p_long) {
  if (rng.chance(p_none)) {
    style.emplace_back("sleeve", 0.0);
    return 0.0;
  }
  return draw(rng, style, "sleeve", rng.chance(p_long) ? p.sleeve_long : p.sleeve_short);
}

// Ease growing below `from` by `flare` per metre down to `hem`.
EaseProfile& flared(EaseProfile& ease, double from, double ease_at, double hem, double flare) {
  ease.at(from, ease_at);
  if (hem < from - 0.01) ease.at(hem, ease_at + flare * (from - hem));
  return ease;
}

void necklines(TopSpec& t, Rng& rng, Style& style, double extra_hi, double front_hi, double back_hi) {
  t.neck_extra = draw(rng, style, "neck_extra", 0.01, extra_hi);
  t.neck_front = draw(rng, style, "neck_front", 0.0, front_hi);
  t.neck_back = draw(rng, style, "neck_back", 0.0, back_hi);
}

void tshirt(const FitContext& ctx, const GarmentParams& p, Rng& rng, Pattern& pattern, Style& style) {
  const Landmarks& m = ctx.marks;
  const double e = draw(rng, style, "ease", p.ease_loose);
  TopSpec t;
  t.hem = m.waist - draw(rng, style, "length", p.top_length) * (m.waist - m.crotch);
  t.ease = EaseProfile().at(t.hem, e + 0.005).at(m.waist, e);
  t.hang = EaseProfile(kHang);
  t.armhole_drop = draw(rng, style, "armhole_drop", 0.01, 0.04);
  t.shoulder_ease = snug(p, e);
  t.sleeve_ease = 0.8 * e;
  necklines(t, rng, style, 0.03, 0.06, 0.02);
  t.sleeve = sleeves(p, rng, style, 0.0, p.long_sleeves);
  const TopQuarters q = build_top(pattern, ctx, t);
  open_quarters(pattern, q.hem);
  open_quarters(pattern, q.neck);
}

void jacket(const FitContext& ctx, const GarmentParams& p, Rng& rng, Pattern& pattern, Style& style, bool hood) {
  const Landmarks& m = ctx.marks;
  const double e = draw(rng, style, "ease", p.layer_clearance);
  TopSpec t;
  t.hem = m.waist - draw(rng, style, "length", p.jacket_length) * (m.waist - m.crotch);
  t.ease = EaseProfile(e);
  t.hang = EaseProfile(kHang);
  t.shoulder_ease = snug(p, e);
  t.sleeve_ease = e;
  t.armhole_drop = draw(rng, style, "armhole_drop", 0.02, 0.04);
  necklines(t, rng, style, 0.03, 0.03, 0.01);
  t.sleeve = draw(rng, style, "sleeve", p.sleeve_long);
  t.split_front = true;
  const TopQuarters q = build_top(pattern, ctx, t);
  open_quarters(pattern, q.hem);
  if (hood) {
    HoodSpec h;
    h.ease = draw(rng, style, "hood_ease", p.hood_ease);
    h.opening = draw(rng, style, "hood_opening", 0.0, 0.5);
    build_hood(pattern, ctx, q.neck, h);
  } else {
    open_quarters(pattern, q.neck);
  }
}

void dress(const FitContext& ctx, const GarmentParams& p, Rng& rng, Pattern& pattern, Style& style, bool belt) {
  const Landmarks& m = ctx.marks;
  const double e = draw(rng, style, "ease", p.ease_fitted);
  const double flare = draw(rng, style, "flare", p.flare);
  const double hem = leg_hem(m, draw(rng, style, "length", p.dress_length), 0.05);
  TopSpec t;
  t.armhole_drop = draw(rng, style, "armhole_drop", 0.01, 0.04);
  t.shoulder_ease = snug(p, e);
  t.sleeve_ease = e + 0.005;
  necklines(t, rng, style, 0.04, 0.1, 0.05);
  t.sleeve = sleeves(p, rng, style, p.sleeveless, 0.0);
  if (!belt) {
    t.hem = hem;
    t.ease.at(m.waist, e);
    flared(t.ease, m.hip, e + 0.01, hem, flare);
    t.hang = EaseProfile().at(m.waist, 0.0).at(m.hip, kHang);
    const TopQuarters q = build_top(pattern, ctx, t);
    open_quarters(pattern, q.hem);
    open_quarters(pattern, q.neck);
    return;
  }
  const double width = draw(rng, style, "belt_width", p.belt_width);
  const double waist = m.waist + draw(rng, style, "waist_shift", -0.02, 0.02);
  const double belt_ease = std::max(p.body_clearance + 0.003, 0.6 * e);
  style.emplace_back("belt_ease", belt_ease);
  const double top = waist + width / 2, bottom = waist - width / 2;
  t.hem = top;
  t.ease.at(top + 0.05, e).at(top, belt_ease).at(bottom, belt_ease);
  flared(t.ease, bottom - 0.05, e + 0.005, hem, flare);
  t.hang = EaseProfile().at(bottom, 0.0).at(bottom - 0.1, kHang);
  const TopQuarters q = build_top(pattern, ctx, t);
  const TubeQuarters band = build_tube(pattern, ctx, "belt", bottom, top, t.ease, t.hang);
  const TubeQuarters skirt = build_tube(pattern, ctx, "skirt", hem, bottom, t.ease, t.hang);
  sew_quarters(pattern, q.hem, band.top);
  sew_quarters(pattern, band.bottom, skirt.top);
  open_quarters(pattern, skirt.bottom);
  open_quarters(pattern, q.neck);
}

void jumpsuit(const FitContext& ctx, const GarmentParams& p, Rng& rng, Pattern& pattern, Style& style) {
  const Landmarks& m = ctx.marks;
  const double e = draw(rng, style, "ease", p.ease_fitted);
  TopSpec t;
  t.hem = m.waist + draw(rng, style, "waist_shift", -0.02, 0.02);
  t.ease = EaseProfile(e);
  t.shoulder_ease = snug(p, e);
  t.sleeve_ease = e;
  t.armhole_drop = draw(rng, style, "armhole_drop", 0.01, 0.03);
  necklines(t, rng, style, 0.03, 0.05, 0.02);
  t.sleeve = sleeves(p, rng, style, p.sleeveless, p.long_sleeves);
  PantsSpec legs;
  legs.waist = t.hem;
  legs.hem = leg_hem(m, draw(rng, style, "length", p.pants_length), 0.04);
  legs.ease = t.ease;
  const TopQuarters q = build_top(pattern, ctx, t);
  sew_quarters(pattern, q.hem, build_pants(pattern, ctx, legs));
  open_quarters(pattern, q.neck);
}

void pants(const FitContext& ctx, const GarmentParams& p, Rng& rng, Pattern& pattern, Style& style) {
  PantsSpec legs;
  legs.ease = EaseProfile(draw(rng, style, "ease", p.ease_pants));
  legs.waist = low_waist(ctx.marks, rng, style);
  legs.hem = leg_hem(ctx.marks, draw(rng, style, "length", p.pants_length), 0.04);
  open_quarters(pattern, build_pants(pattern, ctx, legs));
}

void skirt(const FitContext& ctx, const GarmentParams& p, Rng& rng, Pattern& pattern, Style& style) {
  const Landmarks& m = ctx.marks;
  const double e = draw(rng, style, "ease", p.ease_fitted);
  const double flare = draw(rng, style, "flare", p.flare);
  const double waist = low_waist(m, rng, style);
  const double hem = leg_hem(m, draw(rng, style, "length", p.skirt_length), 0.05);
  EaseProfile ease;
  ease.at(waist, e);
  flared(ease, std::min(m.hip, waist - 0.02), e + 0.005, hem, flare);
  const EaseProfile hang = EaseProfile().at(waist, 0.0).at(waist - 0.1, kHang);
  const TubeQuarters q = build_tube(pattern, ctx, "skirt", hem, waist, ease, hang);
  open_quarters(pattern, q.bottom);
  open_quarters(pattern, q.top);
}

// The types that share a recipe with a variant.
void plain_jacket(const FitContext& c, const GarmentParams& p, Rng& r, Pattern& pattern, Style& style) {
  jacket(c, p, r, pattern, style, false);
}
void hooded_jacket(const FitContext& c, const GarmentParams& p, Rng& r, Pattern& pattern, Style& style) {
  jacket(c, p, r, pattern, style, true);
}
void plain_dress(const FitContext& c, const GarmentParams& p, Rng& r, Pattern& pattern, Style& style) {
  dress(c, p, r, pattern, style, false);
}
void belted_dress(const FitContext& c, const GarmentParams& p, Rng& r, Pattern& pattern, Style& style) {
  dress(c, p, r, pattern, style, true);
}

}  // namespace

const std::vector<Recipe>& recipes() {
  static const std::vector<Recipe> table{{"tshirt", tshirt},
                                         {"jacket", plain_jacket},
                                         {"jacket_hood", hooded_jacket},
                                         {"dress", plain_dress},
                                         {"dress_belt", belted_dress},
                                         {"jumpsuit", jumpsuit},
                                         {"pants", pants},
                                         {"skirt", skirt}};
  return table;
}

void make_pattern(const std::string& type, const FitContext& ctx, const GarmentParams& params, Rng& rng,
                  Pattern& pattern, Style& style) {
  for (const Recipe& recipe : recipes()) {
    if (type == recipe.type) {
      recipe.make(ctx, params, rng, pattern, style);
      return;
    }
  }
  throw Error("garment recipe: unknown type '" + type + "'");
}

}  // namespace layers::garment
