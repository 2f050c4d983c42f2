// The ease a motion's leg spread asks of torso sections, and its skin's
// growth of pants sections (see garment_leg_room.h).
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

// Area of every face of `faces` over the points `p`.
std::vector<double> face_areas(const geometry::Points& p, const geometry::Faces& faces) {
  std::vector<double> out(static_cast<std::size_t>(faces.rows()));
  for (int f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = p.row(faces(f, 0)).cast<double>().transpose();
    const Eigen::Vector3d b = p.row(faces(f, 1)).cast<double>().transpose();
    const Eigen::Vector3d c = p.row(faces(f, 2)).cast<double>().transpose();
    out[static_cast<std::size_t>(f)] = 0.5 * (b - a).cross(c - a).norm();
  }
  return out;
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

EaseProfile hip_room(const TPoseBody& body, const std::vector<geometry::Points>& frames, double max_strain) {
  const Landmarks m = measure(body);
  const auto& rest = body.mesh.vertices;
  const auto& faces = body.mesh.faces;
  const std::vector<double> rest_area = face_areas(rest, faces);
  std::vector<std::vector<double>> area;
  area.reserve(frames.size());
  for (const geometry::Points& f : frames) area.push_back(face_areas(f, faces));
  const double covered = (1.0 + max_strain) * (1.0 + max_strain);  // area ratio capped cloth can follow
  const double low = 0.5 * (m.crotch + m.knee);
  std::vector<double> heights;
  double most = 0.0;
  for (double y = m.waist; y > low; y -= kBandStep) {
    std::vector<int> band;
    for (int f = 0; f < faces.rows(); ++f) {
      const double centre = (rest(faces(f, 0), 1) + rest(faces(f, 1), 1) + rest(faces(f, 2), 1)) / 3.0;
      if (std::abs(centre - y) <= kBandHalf) band.push_back(f);
    }
    std::vector<Vec2> points;
    for (int v = 0; v < rest.rows(); ++v)
      if (std::abs(rest(v, 1) - y) <= kBandHalf) points.emplace_back(rest(v, 0), rest(v, 2));
    if (points.size() < kBandPoints || band.empty()) continue;
    double at_rest = 0.0;
    for (int f : band) at_rest += rest_area[static_cast<std::size_t>(f)];
    double grown = 1.0;
    for (const auto& a : area) {
      double sum = 0.0;
      for (int f : band) sum += a[static_cast<std::size_t>(f)];
      grown = std::max(grown, sum / at_rest);
    }
    const double outline = hull_perimeter(std::move(points));
    most = std::max(most, (1.0 + kLegRoomMargin) * outline * std::max(0.0, grown / covered - 1.0) / (2.0 * M_PI));
    heights.push_back(y);
  }
  // The cloth slides between neighbouring bands, so the whole region gets
  // what its most grown band asks for.
  EaseProfile room;
  room.at(m.waist + kBandStep, 0.0);
  room.at(low - kBandStep, 0.0);
  for (double y : heights) room.at(y, most);
  return room;
}

}  // namespace layers::garment
