// The ease a motion's leg spread asks of torso sections, and its skin's
// growth of pants sections (see garment_leg_room.h).
#include "layers/garment/garment_leg_room.h"

#include <algorithm>
#include <cmath>

#include "layers/garment/garment_section.h"
#include "layers/geometry/normals.h"

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

// Skin vertices of the T-pose within kBandHalf of height y.
std::vector<int> band_vertices(const geometry::Points& rest, double y) {
  std::vector<int> band;
  for (int v = 0; v < rest.rows(); ++v)
    if (std::abs(rest(v, 1) - y) <= kBandHalf) band.push_back(v);
  return band;
}

}  // namespace

EaseProfile leg_room(const TPoseBody& body, const std::vector<geometry::Points>& frames) {
  const Landmarks m = measure(body);
  const auto& rest = body.mesh.vertices;
  EaseProfile room;
  for (double y = m.hip; y > m.ankle + kBandHalf; y -= kBandStep) {
    const std::vector<int> band = band_vertices(rest, y);
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
  const double low = 0.5 * (m.crotch + m.knee);
  // The bands: their faces (by the centre's T-pose height), T-pose area
  // and T-pose outline.
  struct Band {
    double y = 0.0, outline = 0.0, rest_area = 0.0, grown = 1.0;
    std::vector<int> faces;
  };
  const Eigen::VectorXf rest_areas = geometry::face_areas(rest, faces);
  std::vector<Band> bands;
  for (double y = m.waist; y > low; y -= kBandStep) {
    const std::vector<int> vertices = band_vertices(rest, y);
    Band band;
    band.y = y;
    for (int f = 0; f < faces.rows(); ++f) {
      const double centre = (rest(faces(f, 0), 1) + rest(faces(f, 1), 1) + rest(faces(f, 2), 1)) / 3.0;
      if (std::abs(centre - y) > kBandHalf) continue;
      band.faces.push_back(f);
      band.rest_area += rest_areas(f);
    }
    if (vertices.size() < kBandPoints || band.faces.empty()) continue;
    std::vector<Vec2> points;
    for (int v : vertices) points.emplace_back(rest(v, 0), rest(v, 2));
    band.outline = hull_perimeter(std::move(points));
    bands.push_back(std::move(band));
  }
  // Each band's largest area over the motion, one frame at a time.
  for (const geometry::Points& frame : frames) {
    const Eigen::VectorXf areas = geometry::face_areas(frame, faces);
    for (Band& band : bands) {
      double sum = 0.0;
      for (int f : band.faces) sum += areas(f);
      band.grown = std::max(band.grown, sum / band.rest_area);
    }
  }
  // What each band asks for; the cloth slides between neighbouring bands,
  // so the whole region gets what the most grown one asks for.
  const double covered = (1.0 + max_strain) * (1.0 + max_strain);  // area ratio capped cloth can follow
  double most = 0.0;
  for (const Band& band : bands)
    most = std::max(most,
                    (1.0 + kLegRoomMargin) * band.outline * std::max(0.0, band.grown / covered - 1.0) / (2.0 * M_PI));
  EaseProfile room;
  room.at(m.waist + kBandStep, 0.0);
  room.at(low - kBandStep, 0.0);
  for (const Band& band : bands) room.at(band.y, most);
  return room;
}

}  // namespace layers::garment
