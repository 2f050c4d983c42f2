// Leg room: the ease a motion's leg spread asks of torso sections below
// the hips, and a dress built with it going round the spread legs.
#include <gtest/gtest.h>

#include <cmath>

#include "garment_fixture.h"
#include "layers/garment/garment_leg_room.h"
#include "layers/garment/garment_section.h"

namespace layers::garment {
namespace {

// The T-pose skin with the left leg (x > 0, below the crotch) moved
// forward by `step` m: a stride, as far as outlines go.
geometry::Points stride(const TPoseBody& body, double step) {
  const double crotch = measure(body).crotch;
  geometry::Points p = body.mesh.vertices;
  for (int v = 0; v < p.rows(); ++v)
    if (p(v, 0) > 0.0f && p(v, 1) < crotch) p(v, 2) += static_cast<float>(step);
  return p;
}

// Length of the convex outline of the points within `half` of height y
// (2 cm: leg_room's bands).
double outline(const geometry::Points& p, double y, double half = 0.02) {
  std::vector<Vec2> pts;
  for (int v = 0; v < p.rows(); ++v)
    if (std::abs(p(v, 1) - y) <= half) pts.emplace_back(p(v, 0), p(v, 2));
  const std::vector<Vec2> hull = convex_hull(pts);
  double length = 0.0;
  for (std::size_t i = 0; i < hull.size(); ++i) length += (hull[(i + 1) % hull.size()] - hull[i]).norm();
  return length;
}

// Length of a garment's hem: its boundary edges within 1 cm of its lowest vertex.
double hem_length(const GarmentMesh& g) {
  const double lowest = g.vertices.col(1).minCoeff();
  std::map<std::pair<int, int>, int> uses;
  for (int f = 0; f < g.faces.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = g.faces(f, k), b = g.faces(f, (k + 1) % 3);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  double length = 0.0;
  for (const auto& [e, n] : uses)
    if (n == 1 && g.vertices(e.first, 1) < lowest + 0.01 && g.vertices(e.second, 1) < lowest + 0.01)
      length += (g.vertices.row(e.first) - g.vertices.row(e.second)).norm();
  return length;
}

TEST(GarmentLegRoom, NoneWhereTheLegsDoNotSpread) {
  const TPoseBody& body = test::tpose(0);
  const EaseProfile room = leg_room(body, {body.mesh.vertices});
  ASSERT_GT(room.knots.size(), 20u);  // every 2 cm from the hips to the ankles
  for (const auto& [y, e] : room.knots) EXPECT_NEAR(e, 0.0, 1e-9) << "at height " << y;
}

TEST(GarmentLegRoom, AStrideAsksForItsOutlineBelowTheCrotch) {
  const TPoseBody& body = test::tpose(0);
  const Landmarks m = measure(body);
  const geometry::Points spread = stride(body, 0.3);
  const EaseProfile room = leg_room(body, {body.mesh.vertices, spread});
  // At a knot halfway between crotch and knee: the outline's growth, plus
  // the margin, over 2 pi.
  double y = 0.5 * (m.crotch + m.knee), best = 1e9;
  for (const auto& knot : room.knots)
    if (std::abs(knot.first - y) < best) best = std::abs(knot.first - y), y = knot.first;
  const double grown = outline(spread, y) - outline(body.mesh.vertices, y);
  EXPECT_GT(grown, 0.25);  // two legs 30 cm apart
  EXPECT_NEAR(room(y), (1.0 + kLegRoomMargin) * grown / (2 * M_PI), 1e-6);
  EXPECT_EQ(room(m.hip + 0.05), 0.0);  // nothing above the hips
  EXPECT_EQ(room(m.waist), 0.0);
}

TEST(GarmentLegRoom, ADressGoesRoundTheSpreadLegs) {
  const TPoseBody& body = test::tpose(0);
  const geometry::Points spread = stride(body, 0.5);
  const EaseProfile room = leg_room(body, {body.mesh.vertices, spread});
  const GarmentParams params = test::params_at(0.02);
  const GarmentMesh plain = build_garment("dress", body, params, 3);
  const GarmentMesh roomy = build_garment("dress", body, params, 3, {}, &room);
  const double hem = plain.vertices.col(1).minCoeff();
  ASSERT_NEAR(roomy.vertices.col(1).minCoeff(), hem, 0.03);  // same length drawn
  const double legs = outline(spread, hem + 0.01, 0.01);
  EXPECT_LT(hem_length(plain), legs);  // the stride would tear through it
  EXPECT_GT(hem_length(roomy), legs);
  // The bodice keeps its size (up to where the mesh samples it: 3%).
  const double waist = measure(body).waist;
  EXPECT_NEAR(outline(roomy.vertices, waist, 0.01), outline(plain.vertices, waist, 0.01), 0.03);
}

}  // namespace
}  // namespace layers::garment
