// garment_top.cpp -- the top piece: bodice rows on horizontal sections up
// to the garment's armpit, then shoulder columns (sagittal sections at each
// x, from the front or back armpit row up to the shoulder seam or the
// neckline), and sleeves whose rows are the same sagittal sections beyond
// the armpit, closed under the arm. A sleeve's first row is therefore the
// bodice's armhole, point for point.
#include <algorithm>
#include <cmath>
#include <limits>

#include "layers/core/error.h"
#include "layers/garment/garment_pieces.h"
#include "layers/garment/garment_section.h"
#include "layers/garment/garment_tube.h"

namespace layers::garment {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kSlabX = 0.02;         // half-width of the x slab of a sagittal section
constexpr double kUnderarmRise = 0.08;  // distance over which the underarm seam rises to the arm
constexpr double kColumnBlend = 0.1;    // bodice columns turn from even arc length to even x below the armpit
constexpr double kSideBlend = 0.04;     // the shoulder seam slides onto the armpit's z within this of the side
constexpr double kSleeveLoosen = 0.08;  // the sleeve's ease grows to its value over this distance past the armpit

Vec2 zy(const body::Vec3& p) { return {p.z(), p.y()}; }

// The point of an x-monotone polyline at abscissa x (clamped to its ends).
body::Vec3 at_x(const std::vector<body::Vec3>& line, double x) {
  for (std::size_t k = 0; k + 1 < line.size(); ++k) {
    const double x0 = line[k].x(), x1 = line[k + 1].x();
    if ((x - x0) * (x - x1) <= 0 && x0 != x1) return line[k] + (x - x0) / (x1 - x0) * (line[k + 1] - line[k]);
  }
  return std::abs(x - line.front().x()) < std::abs(x - line.back().x()) ? line.front() : line.back();
}

// Angle in [lo, hi] where the section's x equals `x` (x monotone there).
double angle_at_x(const Radial& r, double x, double lo, double hi) {
  const bool rising = r.point(hi).x() > r.point(lo).x();
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    if ((r.point(mid).x() < x) == rising)
      lo = mid;
    else
      hi = mid;
  }
  return 0.5 * (lo + hi);
}

// The polyline up to where it first enters the region where inside() < 0
// (a sign change between two points is located by bisection).
template <class F>
std::vector<body::Vec3> cut_where(std::vector<body::Vec3> line, const F& inside) {
  for (std::size_t k = 1; k < line.size(); ++k) {
    if (inside(line[k]) >= 0) continue;
    body::Vec3 lo = line[k - 1], hi = line[k];
    for (int it = 0; it < 40; ++it) {
      const body::Vec3 mid = 0.5 * (lo + hi);
      (inside(mid) < 0 ? hi : lo) = mid;
    }
    line[k] = hi;
    line.resize(k + 1);
    break;
  }
  return line;
}

// Sagittal sections around the shoulders and arms. Inside the armpits
// (|x| <= a) a section rises from the bodice's top row (front point F,
// back point B, centre between them); beyond, from the underarm seam.
class ShoulderProfile {
 public:
  ShoulderProfile(const FitContext& ctx, std::vector<body::Vec3> front_top, std::vector<body::Vec3> back_top,
                  double shoulder_ease, double sleeve_ease)
      : ctx_(ctx),
        front_(std::move(front_top)),
        back_(std::move(back_top)),
        shoulder_ease_(shoulder_ease),
        sleeve_ease_(sleeve_ease) {
    a_left_ = front_.back().x();
    a_right_ = -front_.front().x();
    y_ap_ = front_.front().y();
  }
  double a_left() const { return a_left_; }
  double a_right() const { return a_right_; }

  Radial at(double x) const {
    const bool torso = x <= a_left_ && x >= -a_right_;
    Vec2 f, b, c;
    if (torso) {
      f = zy(at_x(front_, x));
      b = zy(at_x(back_, x));
      c = 0.5 * (f + b);
      // Near the armpits the section's side can be flat (F and B far apart
      // for nearly the same x): slide the centre onto the armpit there, so
      // that the shoulder seam (straight above the centre) meets the
      // sleeve's top seam without a jump.
      const body::Vec3& armpit = x > 0 ? front_.back() : front_.front();
      const double a = x > 0 ? a_left_ : a_right_;
      c.x() += smooth01((std::abs(x) - (a - kSideBlend)) / kSideBlend) * (armpit.z() - c.x());
    } else {
      f = b = c = underarm(x);
    }
    std::vector<Vec2> pts = body_points(x, c.y());
    pts = dilate(convex_hull(std::move(pts)), ease(x));
    pts.push_back(f);
    pts.push_back(b);
    Radial r = radial_of(convex_hull(std::move(pts)), c, false, 0.0, kPi, 73, 1);
    // End exactly on the base points, blending the difference over ~25 degrees.
    const double df = (f - c).norm() - r.r.front(), db = (b - c).norm() - r.r.back();
    const int n = static_cast<int>(r.r.size());
    for (int k = 0; k < n; ++k) {
      const double psi = kPi * k / (n - 1);
      r.r[k] = std::max(0.0, r.r[k] + df * std::max(0.0, 1 - psi / 0.45) + db * std::max(0.0, 1 - (kPi - psi) / 0.45));
    }
    return r;
  }

  std::vector<body::Vec3> arc(double x, double psi0, double psi1) const {
    return at_abscissa(at(x).arc(psi0, psi1), x);
  }

 private:
  // Snug over the shoulders and at the armhole, looser along the arm.
  double ease(double x) const {
    const double a = x > 0 ? a_left_ : a_right_;
    return shoulder_ease_ + (sleeve_ease_ - shoulder_ease_) * smooth01((std::abs(x) - a) / kSleeveLoosen);
  }

  // Envelope points of the slab at x above height `above`, as (z, y).
  std::vector<Vec2> body_points(double x, double above) const {
    const PartMask mask = kAllParts & ~(kHands | bit(Part::Head) | kFeet);
    std::vector<Vec2> pts;
    for (int i : ctx_.env.slab(0, x - kSlabX, x + kSlabX, mask)) {
      const body::Vec3& p = ctx_.env.point(i);
      if (p.y() < above) continue;
      if (ctx_.env.part(i) == Part::Neck && p.y() > ctx_.marks.neck) continue;
      pts.push_back(zy(p));
    }
    return pts;
  }

  // The underarm seam beyond the armpit, as (z, y): it leaves the armpit
  // and rises to just under the arm.
  Vec2 underarm(double x) const {
    const double a = x > 0 ? a_left_ : a_right_;
    const body::Vec3& armpit = x > 0 ? front_.back() : front_.front();
    const double t = smooth01((std::abs(x) - a) / kUnderarmRise);
    const std::vector<Vec2> pts = body_points(x, y_ap_);
    if (pts.empty()) return zy(armpit);
    double lowest = std::numeric_limits<double>::infinity(), zlo = lowest, zhi = -lowest;
    for (const Vec2& q : pts) {
      lowest = std::min(lowest, q.y());
      zlo = std::min(zlo, q.x());
      zhi = std::max(zhi, q.x());
    }
    const double y = y_ap_ + t * (std::max(y_ap_, lowest - ease(x)) - y_ap_);
    const double z = armpit.z() + t * (0.5 * (zlo + zhi) - armpit.z());
    return {z, y};
  }

  const FitContext& ctx_;
  std::vector<body::Vec3> front_, back_;
  double shoulder_ease_, sleeve_ease_;
  double a_left_ = 0, a_right_ = 0, y_ap_ = 0;
};

// The garment's armpit height: under the lowest arm point of the envelope
// next to the torso (an inner garment's sleeve counts).
double armpit_height(const FitContext& ctx) {
  double lowest = std::numeric_limits<double>::infinity();
  for (int i : ctx.env.slab(1, 0.0, 10.0, kArms))
    if (std::abs(ctx.env.point(i).x()) < ctx.marks.shoulder_x + 0.1) lowest = std::min(lowest, ctx.env.point(i).y());
  return std::isfinite(lowest) ? lowest : ctx.marks.armpit;
}

// The neckline: where the shoulder columns meet a vertical elliptic
// cylinder round the neck, centred on the shoulder seam's z at the
// neckline ends (+-half_width) so that the front and back necklines meet
// the shoulder seams exactly there; it reaches further forward (backward)
// by the front (back) depth.
struct Neckline {
  double half_width, centre_z, depth, front, back;
  Neckline(const FitContext& ctx, const ShoulderProfile& profile, double n_w, const TopSpec& spec)
      : half_width(n_w),
        centre_z(0.5 * (profile.arc(n_w, 0, kPi / 2).back().z() + profile.arc(-n_w, 0, kPi / 2).back().z())),
        depth(ctx.marks.neck_half_depth + spec.neck_extra),
        front(spec.neck_front),
        back(spec.neck_back) {}
  // < 0 inside the cylinder.
  double operator()(const body::Vec3& p) const {
    const double reach = depth + (p.z() > centre_z ? front : back);
    const double u = p.x() / half_width, v = (p.z() - centre_z) / reach;
    return u * u + v * v - 1.0;
  }
};

// The shoulder part of a bodice panel: a column per foot (the armpit row's
// points) up to the shoulder seam or the neckline, resampled to a common
// number of rows (the foot itself excluded).
std::vector<std::vector<body::Vec3>> shoulder_rows(const FitContext& ctx, const ShoulderProfile& profile,
                                                   const Neckline& neck, const std::vector<body::Vec3>& base,
                                                   bool front) {
  std::vector<std::vector<body::Vec3>> cols;
  int n = 2;
  for (const body::Vec3& foot : base) {
    const double x = foot.x();
    std::vector<body::Vec3> col = front ? profile.arc(x, 0, kPi / 2) : profile.arc(x, kPi, kPi / 2);
    if (std::abs(x) < neck.half_width * (1 - 1e-9)) col = cut_where(std::move(col), neck);
    cols.push_back(std::move(col));
    n = std::max(n, static_cast<int>(std::ceil(length(cols.back()) / ctx.step)));
  }
  std::vector<std::vector<body::Vec3>> out(n, std::vector<body::Vec3>(base.size()));
  for (std::size_t j = 0; j < base.size(); ++j) {
    const auto pts = resample(cols[j], n);
    for (int k = 1; k <= n; ++k) out[k - 1][j] = pts[k];
  }
  return out;
}

// A sleeve on the left (+1) or right (-1) armhole: rows are the sagittal
// sections from the armhole out along the arm, each a loop from the
// underarm seam round the front, over the top and back round the back.
void add_sleeve(Pattern& pattern, const FitContext& ctx, const ShoulderProfile& profile, int side, double share,
                const Edge& front_hole, const Edge& back_hole) {
  const double a = side > 0 ? profile.a_left() : profile.a_right();
  const double end = a + share * std::max(0.05, ctx.marks.wrist_x - 0.03 - a);
  const int n_rows = std::max(2, static_cast<int>(std::ceil((end - a) / ctx.step)));
  std::vector<std::vector<body::Vec3>> halves_f, halves_b;
  int m = 2;
  for (int i = 0; i <= n_rows; ++i) {
    const double x = side * (a + (end - a) * i / n_rows);
    const Radial section = profile.at(x);
    halves_f.push_back(at_abscissa(section.arc(0, kPi / 2), x));
    halves_b.push_back(at_abscissa(section.arc(kPi, kPi / 2), x));
    m = std::max({m, static_cast<int>(std::ceil(length(halves_f.back()) / ctx.step)),
                  static_cast<int>(std::ceil(length(halves_b.back()) / ctx.step))});
  }
  std::vector<std::vector<body::Vec3>> loop(n_rows + 1);
  for (int i = 0; i <= n_rows; ++i) {
    loop[i] = resample(halves_f[i], m);
    const auto b = resample(halves_b[i], m);
    loop[i].insert(loop[i].end(), b.rbegin() + 1, b.rend());
  }
  const int sleeve = pattern.add(grid_of(side > 0 ? "sleeve_left" : "sleeve_right", loop));
  pattern.sew({sleeve, Side::Bottom, 0, m}, front_hole);     // cap, armpit -> shoulder, front half
  pattern.sew({sleeve, Side::Bottom, 2 * m, m}, back_hole);  // and back half
  pattern.sew({sleeve, Side::Left, 0, n_rows}, {sleeve, Side::Right, 0, n_rows});  // underarm
  pattern.open({sleeve, Side::Top, 0, 2 * m});                                     // cuff
}

// Columns of the full front, possibly split into two panels at the centre.
struct FrontHalf {
  int panel, offset;
};

}  // namespace

TopQuarters build_top(Pattern& pattern, const FitContext& ctx, const TopSpec& spec) {
  const double y_ap = armpit_height(ctx) - spec.ease(ctx.marks.armpit) - spec.armhole_drop;
  if (y_ap - spec.hem < 4 * ctx.step) throw Error("garment top: hem too close to the armpit");

  // Neckline ends (angles where the armpit row reaches x = +-n_w).
  const Radial top_row = horizontal_section(ctx.env, y_ap, torso_section(ctx, y_ap, spec.ease, spec.hang));
  const double a_min = std::min(top_row.point(0.0).x(), -top_row.point(kPi).x());
  const double n_w = std::min(ctx.marks.neck_half_width + spec.neck_extra, 0.6 * a_min);
  const double fl = angle_at_x(top_row, n_w, 0.0, kPi / 2), fr = angle_at_x(top_row, -n_w, kPi / 2, kPi);
  const double bl = angle_at_x(top_row, n_w, 1.5 * kPi, 2 * kPi), br = angle_at_x(top_row, -n_w, kPi, 1.5 * kPi);
  const std::vector<double> heights = row_heights(spec.hem, y_ap, ctx.step);
  std::vector<double> x_uniform;
  for (double y : heights) x_uniform.push_back(smooth01((y - (y_ap - kColumnBlend)) / kColumnBlend));
  const TubeRows rows = tube_rows(ctx, heights, spec.ease, spec.hang, {kPi, fr, kPi / 2, fl, 0.0},
                                  {2 * kPi, bl, 1.5 * kPi, br, kPi}, x_uniform);
  const int n_a = static_cast<int>(rows.front.size()) - 1;  // armpit row
  const ShoulderProfile profile(ctx, rows.front.back(), rows.back.back(), spec.shoulder_ease, spec.sleeve_ease);

  const Neckline neck(ctx, profile, n_w, spec);
  auto grid_rows = [&](std::vector<std::vector<body::Vec3>> lower, bool front) {
    const auto upper = shoulder_rows(ctx, profile, neck, lower.back(), front);
    lower.insert(lower.end(), upper.begin(), upper.end());
    return lower;
  };
  const auto front_rows = grid_rows(rows.front, true);
  const auto back_rows = grid_rows(rows.back, false);
  const int top_f = static_cast<int>(front_rows.size()) - 1, top_b = static_cast<int>(back_rows.size()) - 1;
  const auto& kf = rows.front_knot_cols;  // right side, right neck, centre, left neck, left side
  const auto& kb = rows.back_knot_cols;   // left side, left neck, centre, right neck, right side

  FrontHalf right{0, 0}, left{0, 0};
  if (spec.split_front) {
    std::vector<std::vector<body::Vec3>> r(front_rows.size()), l(front_rows.size());
    for (std::size_t i = 0; i < front_rows.size(); ++i) {
      r[i].assign(front_rows[i].begin(), front_rows[i].begin() + kf[2] + 1);
      l[i].assign(front_rows[i].begin() + kf[2], front_rows[i].end());
    }
    right = {pattern.add(grid_of("front_right", r)), 0};
    left = {pattern.add(grid_of("front_left", l)), kf[2]};
    pattern.sew({right.panel, Side::Right, 0, top_f}, {left.panel, Side::Left, 0, top_f});  // zip
  } else {
    right = left = {pattern.add(grid_of("front", front_rows)), 0};
  }
  const int back = pattern.add(grid_of("back", back_rows));
  auto front_edge = [](const FrontHalf& h, Side side, int j0, int j1) {
    return Edge{h.panel, side, j0 - h.offset, j1 - h.offset};
  };

  // Side seams, shoulder seams.
  pattern.sew({right.panel, Side::Left, 0, n_a}, {back, Side::Right, 0, n_a});
  pattern.sew({left.panel, Side::Right, 0, n_a}, {back, Side::Left, 0, n_a});
  pattern.sew(front_edge(right, Side::Top, kf[0], kf[1]), {back, Side::Top, kb[4], kb[3]});
  pattern.sew(front_edge(left, Side::Top, kf[4], kf[3]), {back, Side::Top, kb[0], kb[1]});

  // Armholes: sleeves or openings. side +1 = left arm (+x).
  for (int side : {+1, -1}) {
    const Edge front_hole =
        side > 0 ? Edge{left.panel, Side::Right, n_a, top_f} : Edge{right.panel, Side::Left, n_a, top_f};
    const Edge back_hole = side > 0 ? Edge{back, Side::Left, n_a, top_b} : Edge{back, Side::Right, n_a, top_b};
    if (spec.sleeve <= 0) {
      pattern.open(front_hole);
      pattern.open(back_hole);
      continue;
    }
    add_sleeve(pattern, ctx, profile, side, spec.sleeve, front_hole, back_hole);
  }

  TopQuarters q;
  q.hem = {front_edge(left, Side::Bottom, kf[2], kf[4]),
           front_edge(right, Side::Bottom, kf[2], kf[0]),
           {back, Side::Bottom, kb[2], kb[0]},
           {back, Side::Bottom, kb[2], kb[4]}};
  q.neck = {front_edge(left, Side::Top, kf[2], kf[3]),
            front_edge(right, Side::Top, kf[2], kf[1]),
            {back, Side::Top, kb[2], kb[1]},
            {back, Side::Top, kb[2], kb[3]}};
  return q;
}

}  // namespace layers::garment
