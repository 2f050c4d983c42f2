// The ease a motion's leg spread asks of torso sections (see garment_leg_room.h).
#include "layers/garment/garment_leg_room.h"

#include <algorithm>
#include <cmath>

#include "layers/garment/garment_section.h"

namespace layers::garment {
namespace {

constexpr double kBandStep = 0.02;      // m between knots
constexpr double kBandHalf = 0.02;      // m: skin within this of a knot's height belongs to it (bands overlap:
                                        // the skin's rows are up to 3 cm apart along the shins)
constexpr std::size_t kBandPoints = 8;  // fewer skin vertices in a band: no knot there

double hull_perimeter(std::vector<Vec2> points) {
  if (points.size() < 3) return 0.0;
  const std::vector<Vec2> hull = convex_hull(std::move(points));
  return length(hull) + (hull.front() - hull.back()).norm();
}

}  // namespace

EaseProfile leg_room(const TPoseBody& body, const std::vector<geometry::Points>& frames) {
  const Landmarks m = measure(body);
  const auto& rest = body.mesh.vertices;
  EaseProfile room;
  for (double y = m.hip; y > m.ankle + kBandHalf; y -= kBandStep) {
    std::vector<int> band;
    for (int v = 0; v < rest.rows(); ++v)
      if (std::abs(rest(v, 1) - y) <= kBandHalf) band.push_back(v);
    if (band.size() < kBandPoints) continue;
    std::vector<Vec2> points(band.size());
    const auto outline = [&](const geometry::Points& p) {
      for (std::size_t i = 0; i < band.size(); ++i) points[i] = Vec2(p(band[i], 0), p(band[i], 2));
      return hull_perimeter(points);
    };
    const double at_rest = outline(rest);
    double widest = 0.0;
    for (const geometry::Points& f : frames) widest = std::max(widest, outline(f));
    room.at(y, (1.0 + kLegRoomMargin) * std::max(0.0, widest - at_rest) / (2.0 * M_PI));
  }
  // Nothing above the hips (the profile is constant beyond its knots).
  room.at(m.hip + kBandStep, 0.0);
  return room;
}

}  // namespace layers::garment
