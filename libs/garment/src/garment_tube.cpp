// garment_tube.cpp -- shared piece plumbing (quarters, edge points, ease
// profiles) and the tube piece: front and back panels wrapped on
// horizontal sections, split at the sides (angle 0 and pi) and centred on
// the midline (pi/2 front, 3 pi/2 back).
#include <algorithm>
#include <cmath>

#include "layers/core/error.h"
#include "layers/garment/garment_pieces.h"
#include "layers/garment/garment_section.h"
#include "layers/garment/garment_tube.h"

namespace layers::garment {

void sew_quarters(Pattern& pattern, const Quarters& a, const Quarters& b) {
  pattern.sew(a.fl, b.fl);
  pattern.sew(a.fr, b.fr);
  pattern.sew(a.bl, b.bl);
  pattern.sew(a.br, b.br);
}

void open_quarters(Pattern& pattern, const Quarters& q) {
  for (const Edge& e : q.all()) pattern.open(e);
}

std::vector<body::Vec3> edge_points(const Pattern& pattern, const Edge& e) {
  const PanelGrid& g = pattern.panels[e.panel];
  std::vector<body::Vec3> out;
  const int step = e.to >= e.from ? 1 : -1;
  for (int k = e.from;; k += step) {
    switch (e.side) {
      case Side::Bottom:
        out.push_back(g.at(0, k));
        break;
      case Side::Top:
        out.push_back(g.at(g.rows - 1, k));
        break;
      case Side::Left:
        out.push_back(g.at(k, 0));
        break;
      case Side::Right:
        out.push_back(g.at(k, g.cols - 1));
        break;
    }
    if (k == e.to) break;
  }
  return out;
}

EaseProfile& EaseProfile::at(double y, double ease) {
  knots.emplace_back(y, ease);
  std::sort(knots.begin(), knots.end());
  return *this;
}

double EaseProfile::operator()(double y) const {
  if (knots.empty()) throw Error("garment ease profile has no knots");
  if (y <= knots.front().first) return knots.front().second;
  if (y >= knots.back().first) return knots.back().second;
  for (std::size_t k = 1; k < knots.size(); ++k)
    if (y <= knots[k].first) {
      const auto& [y0, e0] = knots[k - 1];
      const auto& [y1, e1] = knots[k];
      return e0 + (e1 - e0) * (y - y0) / (y1 - y0);
    }
  return knots.back().second;
}

namespace {

// Arc-length fractions of n + 1 columns on a segment: uniform in arc
// length, blended with weight w towards uniform in x.
std::vector<double> column_fractions(const std::vector<body::Vec3>& arc, int n, double w) {
  std::vector<double> s(arc.size(), 0.0);
  for (std::size_t i = 1; i < arc.size(); ++i) s[i] = s[i - 1] + (arc[i] - arc[i - 1]).norm();
  std::vector<double> out(n + 1);
  const double x0 = arc.front().x(), x1 = arc.back().x();
  std::size_t k = 1;
  for (int j = 0; j <= n; ++j) {
    const double even = static_cast<double>(j) / n;
    double by_x = even;
    if (w > 0 && x1 != x0 && s.back() > 0) {
      const double target = x0 + (x1 - x0) * even;
      while (k + 1 < arc.size() && (arc[k].x() - target) * (x1 - x0) < 0) ++k;
      const double dx = arc[k].x() - arc[k - 1].x();
      const double f = dx != 0 ? std::clamp((target - arc[k - 1].x()) / dx, 0.0, 1.0) : 0.0;
      by_x = (s[k - 1] + f * (s[k] - s[k - 1])) / s.back();
    }
    out[j] = (1 - w) * even + w * by_x;
  }
  out.front() = 0.0;
  out.back() = 1.0;
  return out;
}

}  // namespace

SectionSpec torso_section(const FitContext& ctx, double y, const EaseProfile& ease, const EaseProfile& hang) {
  SectionSpec spec;
  spec.parts = kTorsoParts;
  spec.ease = ctx.room && !ctx.room->legs.empty() ? std::max(ease(y), ctx.room->legs(y)) : ease(y);
  spec.hang = hang(y);
  return spec;
}

TubeRows tube_rows(const FitContext& ctx, const std::vector<double>& heights, const EaseProfile& ease,
                   const EaseProfile& hang, const std::vector<double>& front_knots,
                   const std::vector<double>& back_knots, const std::vector<double>& x_uniform) {
  TubeRows out;
  std::vector<Radial> sections;
  for (double y : heights) sections.push_back(horizontal_section(ctx.env, y, torso_section(ctx, y, ease, hang)));
  auto build = [&](const std::vector<double>& knots, std::vector<std::vector<body::Vec3>>& rows,
                   std::vector<int>& cols) {
    const int segs = static_cast<int>(knots.size()) - 1;
    std::vector<int> count(segs, 1);
    std::vector<std::vector<std::vector<body::Vec3>>> arcs(heights.size());
    for (std::size_t i = 0; i < heights.size(); ++i)
      for (int s = 0; s < segs; ++s) {
        arcs[i].push_back(at_height(sections[i].arc(knots[s], knots[s + 1]), heights[i]));
        count[s] = std::max(count[s], static_cast<int>(std::ceil(length(arcs[i].back()) / ctx.step)));
      }
    cols.assign(1, 0);
    for (int s = 0; s < segs; ++s) cols.push_back(cols.back() + count[s]);
    rows.assign(heights.size(), {});
    for (std::size_t i = 0; i < heights.size(); ++i)
      for (int s = 0; s < segs; ++s) {
        const double w = x_uniform.empty() ? 0.0 : x_uniform[i];
        const auto pts = resample_at(arcs[i][s], column_fractions(arcs[i][s], count[s], w));
        rows[i].insert(rows[i].end(), pts.begin() + (s == 0 ? 0 : 1), pts.end());
      }
  };
  build(front_knots, out.front, out.front_knot_cols);
  build(back_knots, out.back, out.back_knot_cols);
  out.sections = std::move(sections);
  return out;
}

std::vector<double> row_heights(double y0, double y1, double step) {
  const int n = std::max(2, static_cast<int>(std::ceil((y1 - y0) / step)));
  std::vector<double> ys(n + 1);
  for (int i = 0; i <= n; ++i) ys[i] = y0 + (y1 - y0) * i / n;
  return ys;
}

PanelGrid grid_of(const std::string& name, const std::vector<std::vector<body::Vec3>>& rows) {
  PanelGrid g(name, static_cast<int>(rows.size()), static_cast<int>(rows[0].size()));
  for (int i = 0; i < g.rows; ++i)
    for (int j = 0; j < g.cols; ++j) g.at(i, j) = rows[i][j];
  return g;
}

TubeQuarters build_tube(Pattern& pattern, const FitContext& ctx, const std::string& name, double y0, double y1,
                        const EaseProfile& ease, const EaseProfile& hang) {
  constexpr double kPi = 3.14159265358979323846;
  const TubeRows rows =
      tube_rows(ctx, row_heights(y0, y1, ctx.step), ease, hang, {kPi, kPi / 2, 0.0}, {2 * kPi, 1.5 * kPi, kPi});
  const int front = pattern.add(grid_of(name + "_front", rows.front));
  const int back = pattern.add(grid_of(name + "_back", rows.back));
  const int jf = rows.front_knot_cols[1], Jf = rows.front_knot_cols.back();
  const int jb = rows.back_knot_cols[1], Jb = rows.back_knot_cols.back();
  const int top = static_cast<int>(rows.front.size()) - 1;
  // Sides: the front's left column (x < 0) meets the back's right column.
  pattern.sew({front, Side::Left, 0, top}, {back, Side::Right, 0, top});
  pattern.sew({front, Side::Right, 0, top}, {back, Side::Left, 0, top});
  TubeQuarters q;
  q.bottom = {{front, Side::Bottom, jf, Jf},
              {front, Side::Bottom, jf, 0},
              {back, Side::Bottom, jb, 0},
              {back, Side::Bottom, jb, Jb}};
  q.top = {{front, Side::Top, jf, Jf}, {front, Side::Top, jf, 0}, {back, Side::Top, jb, 0}, {back, Side::Top, jb, Jb}};
  return q;
}

}  // namespace layers::garment
