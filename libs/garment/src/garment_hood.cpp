// garment_hood.cpp -- the hood piece: two side panels sewn to a neckline
// and to each other along a centre seam in the x = 0 plane (over the head,
// from the back of the neck to the forehead). Each panel's columns rise
// from a neckline point to a centre-seam point around the head's centre,
// bending through a waypoint beside the head (behind it for the back
// columns, beside the cheek for the front one: the free face opening);
// their radius leaves the neckline and settles on the head's support
// function plus the ease, so the hood clears the head. Each column first
// climbs straight up from the neckline, so the hood's first rows stay
// clear of the body panels' collar rows.
#include <algorithm>
#include <cmath>

#include "layers/core/error.h"
#include "layers/garment/garment_pieces.h"
#include "layers/garment/garment_section.h"
#include "layers/garment/garment_tube.h"

namespace layers::garment {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Support function of the head and neck points around a centre.
class HeadShape {
 public:
  HeadShape(const Envelope& env, const body::Vec3& centre) : centre_(centre) {
    for (int i : env.slab(1, -1e9, 1e9, kHeadNeck)) points_.push_back(env.point(i) - centre);
    if (points_.empty()) throw Error("garment hood: no head points");
  }
  double support(const body::Vec3& d) const {
    double h = 0;
    for (const body::Vec3& p : points_) h = std::max(h, p.dot(d));
    return h;
  }
  const body::Vec3& centre() const { return centre_; }

 private:
  body::Vec3 centre_;
  std::vector<body::Vec3> points_;
};

body::Vec3 slerp_dir(const body::Vec3& a, const body::Vec3& b, double t) {
  const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0));
  if (angle < 1e-6) return a;
  return (std::sin((1 - t) * angle) * a + std::sin(t * angle) * b) / std::sin(angle);
}

// How a column leaves the neckline. The head centre lies 10-25 cm above
// a front neckline, so a column that turned about it from the start would
// run out sideways along the collar rows of the body panels below and
// cross them (120-180 face pairs per jacket before these three rules).
constexpr double kClimb = 0.3;  // the first 30% of a column blends in from a straight climb
constexpr double kRise = 0.6;   // rad: its direction turns up by at least this before heading for the waypoint

// Left hood panel on the back and front necklines (each from the centre
// line to the side); `split` is the grid column of the side point.
PanelGrid hood_panel(const FitContext& ctx, const HeadShape& head, const std::vector<body::Vec3>& back_neck,
                     const std::vector<body::Vec3>& front_neck, const HoodSpec& spec, int& split, int& rows) {
  const body::Vec3& h = head.centre();
  const int c1 = std::max(2, static_cast<int>(std::ceil(length(back_neck) / ctx.step)));
  const int c2 = std::max(2, static_cast<int>(std::ceil(length(front_neck) / ctx.step)));
  std::vector<body::Vec3> neck = resample(back_neck, c1);
  const auto front = resample(front_neck, c2);  // centre front -> side
  neck.insert(neck.end(), front.rbegin() + 1, front.rend());
  const int cols = c1 + c2;
  split = c1;

  // Centre seam: from above the back of the neck over the head to the forehead.
  auto sagittal = [&](double a) {
    const body::Vec3 d(0, std::sin(a), std::cos(a));
    return body::Vec3(h + (head.support(d) + spec.ease) * d);
  };
  const body::Vec3 b = neck.front() - h;
  const double a_back = std::atan2(b.y(), b.z()) + 2 * kPi - 0.35, a_front = 0.75;
  std::vector<body::Vec3> seam_line;
  for (int k = 0; k <= 96; ++k) seam_line.push_back(sagittal(a_back + (a_front - a_back) * k / 96.0));
  const auto seam = resample(seam_line, cols);

  // Columns, then a common row count by the longest column. Column j
  // runs from its neckline point past a waypoint halfway up between its
  // ends (behind the head for j = 0, round the side, beside the cheek for
  // the face opening, j = cols) to its centre-seam point.
  const double cheek = 0.9 + 0.5 * spec.opening;  // 52 to 80 degrees round from the front
  std::vector<std::vector<body::Vec3>> columns(cols + 1);
  int n = 2;
  for (int j = 0; j <= cols; ++j) {
    const body::Vec3 d0 = (neck[j] - h).normalized(), d1 = (seam[j] - h).normalized();
    const double azimuth = kPi - (kPi - cheek) * static_cast<double>(j) / cols;
    const double elevation =
        0.5 * (std::asin(std::clamp(d0.y(), -1.0, 1.0)) + std::asin(std::clamp(d1.y(), -1.0, 1.0)));
    const body::Vec3 w(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                       std::cos(elevation) * std::cos(azimuth));
    // u: d0 turned up (same azimuth) by kRise, or to the waypoint's
    // elevation if that is higher; the direction runs d0 -> u -> w -> d1.
    const double a0 = std::atan2(d0.x(), d0.z());
    const double rise = std::max(elevation, std::asin(std::clamp(d0.y(), -1.0, 1.0)) + kRise);
    const body::Vec3 u(std::cos(rise) * std::sin(a0), std::sin(rise), std::cos(rise) * std::cos(a0));
    const double r0 = (neck[j] - h).norm();
    const double climb = (seam[j] - neck[j]).norm();
    for (int k = 0; k <= 48; ++k) {
      const double t = k / 48.0;
      const body::Vec3 a = slerp_dir(d0, u, t), b = slerp_dir(u, w, t), c = slerp_dir(w, d1, t);
      const body::Vec3 d = slerp_dir(slerp_dir(a, b, t), slerp_dir(b, c, t), t).normalized();
      const double target = head.support(d) + spec.ease;
      // The radius shrinks towards the head's outline from the start but
      // grows only once the column has turned upwards.
      const double settle = target < r0 ? smooth01(t / 0.3) : smooth01((t - 0.15) / 0.35);
      const double r = k == 48 ? (seam[j] - h).norm() : (1 - settle) * r0 + settle * target;
      const body::Vec3 up = neck[j] + body::Vec3(0, t * climb, 0);
      const double blend = smooth01(t / kClimb);
      columns[j].push_back((1 - blend) * up + blend * (h + r * d));
    }
    n = std::max(n, static_cast<int>(std::ceil(length(columns[j]) / ctx.step)));
  }
  PanelGrid g("hood", n + 1, cols + 1);
  for (int j = 0; j <= cols; ++j) {
    const auto pts = resample(columns[j], n);
    for (int i = 0; i <= n; ++i) g.at(i, j) = pts[i];
  }
  rows = n;
  return g;
}

std::vector<body::Vec3> mirrored(std::vector<body::Vec3> line) {
  for (body::Vec3& p : line) p.x() = -p.x();
  return line;
}

}  // namespace

void build_hood(Pattern& pattern, const FitContext& ctx, const Quarters& neck, const HoodSpec& spec) {
  const HeadShape left_head(ctx.env, ctx.marks.head_centre);
  const Envelope flipped = ctx.env.mirrored();
  body::Vec3 flipped_centre = ctx.marks.head_centre;
  flipped_centre.x() = -flipped_centre.x();
  const HeadShape right_head(flipped, flipped_centre);

  int split_l = 0, rows_l = 0, split_r = 0, rows_r = 0;
  PanelGrid left =
      hood_panel(ctx, left_head, edge_points(pattern, neck.bl), edge_points(pattern, neck.fl), spec, split_l, rows_l);
  PanelGrid right = hood_panel(ctx, right_head, mirrored(edge_points(pattern, neck.br)),
                               mirrored(edge_points(pattern, neck.fr)), spec, split_r, rows_r);
  for (body::Vec3& p : right.points) p.x() = -p.x();
  left.name = "hood_left";
  right.name = "hood_right";
  const int cols_l = left.cols - 1, cols_r = right.cols - 1;
  const int l = pattern.add(std::move(left)), r = pattern.add(std::move(right));
  pattern.sew({l, Side::Bottom, 0, split_l}, neck.bl);
  pattern.sew({l, Side::Bottom, cols_l, split_l}, neck.fl);
  pattern.sew({r, Side::Bottom, 0, split_r}, neck.br);
  pattern.sew({r, Side::Bottom, cols_r, split_r}, neck.fr);
  pattern.sew({l, Side::Left, 0, rows_l}, {r, Side::Left, 0, rows_r});
  pattern.sew({l, Side::Top, 0, cols_l}, {r, Side::Top, 0, cols_r});
  pattern.open({l, Side::Right, 0, rows_l});
  pattern.open({r, Side::Right, 0, rows_r});
}

}  // namespace layers::garment
