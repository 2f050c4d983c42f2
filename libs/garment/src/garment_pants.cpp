// garment_pants.cpp -- the pants piece: per leg, a front and a back panel
// on horizontal sections of that leg (envelope points on its side of the
// midline). Below the crotch point the leg section is a closed loop split
// at its innermost point (inseam) and at angle 0 (outseam); above it the
// loop crosses the midline and the panels end there (centre seams), and
// towards the waist the rows blend into the whole-body section. The right
// leg is the left one built on the mirrored envelope. The motion's hip room
// (garment_leg_room.h) loosens the sections, not the crotch.
#include <algorithm>
#include <cmath>

#include "layers/core/error.h"
#include "layers/garment/garment_pieces.h"
#include "layers/garment/garment_section.h"
#include "layers/garment/garment_tube.h"

namespace layers::garment {
namespace {

constexpr double kPi = 3.14159265358979323846;

SectionSpec leg_spec(double ease) {
  SectionSpec s;
  s.parts = kTorsoParts;
  s.ease = ease;
  s.side = +1;
  s.centre_on_midline = false;
  return s;
}

SectionSpec body_spec(double ease) {
  SectionSpec s;
  s.parts = kTorsoParts;
  s.ease = ease;
  return s;
}

// Innermost angle of a (left) leg section, searched on its inner half.
double inseam_angle(const Radial& leg) {
  double best = kPi, best_x = leg.point(kPi).x();
  for (int k = 0; k <= 360; ++k) {
    const double a = kPi / 2 + kPi * k / 360;
    const double x = leg.point(a).x();
    if (x < best_x) best_x = x, best = a;
  }
  return best;
}

// Angle in [lo, hi] where x crosses 0 (x(lo) > 0 >= x(hi) assumed).
double midline_angle(const Radial& r, double lo, double hi) {
  for (int it = 0; it < 50; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (r.point(mid).x() > 0)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

std::vector<body::Vec3> blend(const std::vector<body::Vec3>& a, const std::vector<body::Vec3>& b, double w) {
  const int n = 96;
  const auto ra = resample(a, n), rb = resample(b, n);
  std::vector<body::Vec3> out(n + 1);
  for (int k = 0; k <= n; ++k) out[k] = (1 - w) * ra[k] + w * rb[k];
  return out;
}

// Height where the left leg section first reaches the midline, going up.
double crotch_point(const Envelope& env, const PantsSpec& spec, double hem, double top) {
  auto min_x = [&](double y) {
    const Radial leg = horizontal_section(env, y, leg_spec(spec.ease(y)));
    return leg.point(inseam_angle(leg)).x();
  };
  double lo = hem, hi = hem;
  for (double y = hem; y <= top; y += 0.005) {
    if (min_x(y) <= 0) break;
    lo = y;
    hi = y + 0.005;
  }
  for (int it = 0; it < 20; ++it) {
    const double mid = 0.5 * (lo + hi);
    if (min_x(mid) > 0)
      lo = mid;
    else
      hi = mid;
  }
  return std::min(lo, top);
}

constexpr double kMidlineGap = 0.005;  // m a leg section below the crotch keeps from the midline
constexpr double kWaistTaper = 0.05;   // m over which hip room fades out towards the waistband

// Ease of the pants' section at height y: the garment's own, or the
// motion's hip room where that is larger. Below the crotch the room stops
// where the leg section would reach within kMidlineGap of the midline; it
// fades to none at the waistband, which is sewn to a top or left open at
// the garment's own size.
double section_ease(const FitContext& ctx, const Envelope& env, const PantsSpec& spec, double y, bool below_crotch) {
  const double own = spec.ease(y);
  if (!ctx.room || ctx.room->hips.empty()) return own;
  double room = ctx.room->hips(y) * smooth01((spec.waist - y) / kWaistTaper);
  if (room <= own) return own;
  if (below_crotch) {
    const Radial leg = horizontal_section(env, y, leg_spec(own));
    room = std::min(room, own + std::max(0.0, leg.point(inseam_angle(leg)).x() - kMidlineGap));
  }
  return std::max(own, room);
}

struct LegPanels {
  int front, back, crotch_row, top_row, front_cols, back_cols;
};

// Front and back panel of the left leg of `env`; `mirror` flips the
// placed points to the right side.
LegPanels build_leg(Pattern& pattern, const FitContext& ctx, const Envelope& env, const PantsSpec& spec, double crotch,
                    double blend_top, bool mirror) {
  std::vector<double> ys = row_heights(spec.hem, crotch, ctx.step);
  const auto upper = row_heights(crotch, spec.waist, ctx.step);
  const int crotch_row = static_cast<int>(ys.size()) - 1;
  ys.insert(ys.end(), upper.begin() + 1, upper.end());
  std::vector<std::vector<body::Vec3>> front, back;
  for (std::size_t i = 0; i < ys.size(); ++i) {
    const double y = ys[i], e = section_ease(ctx, env, spec, y, static_cast<int>(i) <= crotch_row);
    const double w = static_cast<int>(i) <= crotch_row ? 0.0 : smooth01((y - crotch) / (blend_top - crotch));
    std::vector<body::Vec3> f, b;
    if (w < 1) {
      const Radial leg = horizontal_section(env, y, leg_spec(e));
      const double in = inseam_angle(leg);
      double af = in, ab = in;
      if (static_cast<int>(i) > crotch_row && leg.point(in).x() < 0) {
        af = midline_angle(leg, kPi / 2, in);
        ab = midline_angle(leg, 1.5 * kPi, in);
      }
      f = at_height(leg.arc(af, 0.0), y);
      b = at_height(leg.arc(ab, 2 * kPi), y);
    }
    if (w > 0) {
      const Radial body = horizontal_section(env, y, body_spec(e));
      const auto bf = at_height(body.arc(kPi / 2, 0.0), y), bb = at_height(body.arc(1.5 * kPi, 2 * kPi), y);
      f = w < 1 ? blend(f, bf, w) : bf;
      b = w < 1 ? blend(b, bb, w) : bb;
    }
    front.push_back(std::move(f));
    back.push_back(std::move(b));
  }
  auto to_grid = [&](std::vector<std::vector<body::Vec3>>& rows, const char* name) {
    int n = 2;
    for (const auto& r : rows) n = std::max(n, static_cast<int>(std::ceil(length(r) / ctx.step)));
    for (auto& r : rows) {
      r = resample(r, n);
      if (mirror)
        for (body::Vec3& p : r) p.x() = -p.x();
    }
    return std::make_pair(pattern.add(grid_of(std::string(mirror ? "pants_right_" : "pants_left_") + name, rows)), n);
  };
  const auto [fp, fn] = to_grid(front, "front");
  const auto [bp, bn] = to_grid(back, "back");
  return {fp, bp, crotch_row, static_cast<int>(ys.size()) - 1, fn, bn};
}

}  // namespace

Quarters build_pants(Pattern& pattern, const FitContext& ctx, const PantsSpec& spec) {
  const Envelope mirrored = ctx.env.mirrored();
  const double limit = std::min(ctx.marks.crotch - 0.01, spec.waist - 4 * ctx.step);
  const double crotch =
      std::min(crotch_point(ctx.env, spec, spec.hem, limit), crotch_point(mirrored, spec, spec.hem, limit));
  if (crotch - spec.hem < 3 * ctx.step) throw Error("garment pants: hem too close to the crotch");
  const double blend_top = std::min(spec.waist - ctx.step, std::max(ctx.marks.hip_joint, crotch + 0.1));
  const LegPanels l = build_leg(pattern, ctx, ctx.env, spec, crotch, blend_top, false);
  const LegPanels r = build_leg(pattern, ctx, mirrored, spec, crotch, blend_top, true);
  const int k = l.crotch_row, top = l.top_row;
  for (const LegPanels& p : {l, r}) {
    pattern.sew({p.front, Side::Right, 0, top}, {p.back, Side::Right, 0, top});  // outseam
    pattern.sew({p.front, Side::Left, 0, k}, {p.back, Side::Left, 0, k});        // inseam
    pattern.open({p.front, Side::Bottom, 0, p.front_cols});
    pattern.open({p.back, Side::Bottom, 0, p.back_cols});
  }
  pattern.sew({l.front, Side::Left, k, top}, {r.front, Side::Left, k, top});  // centre front
  pattern.sew({l.back, Side::Left, k, top}, {r.back, Side::Left, k, top});    // centre back
  return {{l.front, Side::Top, 0, l.front_cols},
          {r.front, Side::Top, 0, r.front_cols},
          {l.back, Side::Top, 0, l.back_cols},
          {r.back, Side::Top, 0, r.back_cols}};
}

}  // namespace layers::garment
