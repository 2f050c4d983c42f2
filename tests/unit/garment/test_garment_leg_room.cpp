// Leg room: the ease a motion's leg spread asks of torso sections below
// the hips, and a dress built with it going round the spread legs. Hip
// room: the ease the skin's growth at the seat asks of pants sections,
// and pants built with it looser there with their crotch where it was.
#include <gtest/gtest.h>

#include <algorithm>
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

// The height of the knot of `room` nearest to y.
double nearest_knot(const EaseProfile& room, double y) {
  double best = room.knots.front().first;
  for (const auto& knot : room.knots)
    if (std::abs(knot.first - y) < std::abs(best - y)) best = knot.first;
  return best;
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
  const double y = nearest_knot(room, 0.5 * (m.crotch + m.knee));
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
  MotionRoom motion;
  motion.legs = room;
  const GarmentMesh roomy = build_garment("dress", body, params, 3, {}, &motion);
  const double hem = plain.vertices.col(1).minCoeff();
  ASSERT_NEAR(roomy.vertices.col(1).minCoeff(), hem, 0.03);  // same length drawn
  const double legs = outline(spread, hem + 0.01, 0.01);
  EXPECT_LT(hem_length(plain), legs);  // the stride would tear through it
  EXPECT_GT(hem_length(roomy), legs);
  // The bodice keeps its size (up to where the mesh samples it: 3%).
  const double waist = measure(body).waist;
  EXPECT_NEAR(outline(roomy.vertices, waist, 0.01), outline(plain.vertices, waist, 0.01), 0.03);
}

// The T-pose skin pushed out from the vertical axis through the body's
// centre (in x and z) by `scale` between heights lo and hi, easing from 1
// over `ramp` on either side: the skin there grows round the body, as far
// as areas go.
geometry::Points swollen(const TPoseBody& body, double lo, double hi, double scale, double ramp) {
  geometry::Points p = body.mesh.vertices;
  for (int v = 0; v < p.rows(); ++v) {
    const double y = p(v, 1);
    const double t = std::clamp(std::min(y - (lo - ramp), (hi + ramp) - y) / ramp, 0.0, 1.0);
    const float s = static_cast<float>(1.0 + (scale - 1.0) * t);
    p(v, 0) *= s;
    p(v, 2) *= s;
  }
  return p;
}

// The lowest garment vertex within 2 mm of the midline (x = 0) and above
// `above`: where the pants' crotch seam ends.
double crotch_of(const GarmentMesh& g, double above) {
  double lowest = 1e9;
  for (int v = 0; v < g.vertices.rows(); ++v)
    if (std::abs(g.vertices(v, 0)) < 0.002 && g.vertices(v, 1) > above)
      lowest = std::min(lowest, static_cast<double>(g.vertices(v, 1)));
  return lowest;
}

TEST(GarmentHipRoom, NoneWhereTheSkinDoesNotGrow) {
  const TPoseBody& body = test::tpose(0);
  const EaseProfile room = hip_room(body, {body.mesh.vertices}, 0.08);
  ASSERT_GT(room.knots.size(), 8u);  // every 2 cm from the waist to mid-thigh
  for (const auto& [y, e] : room.knots) EXPECT_NEAR(e, 0.0, 1e-9) << "at height " << y;
}

TEST(GarmentHipRoom, SkinGrownBeyondTheCapAsksForTheRest) {
  const TPoseBody& body = test::tpose(0);
  const Landmarks m = measure(body);
  // The seat, from 6 cm above the crotch to 10 cm below the waist, 25%
  // wider, easing in over 10 cm: its faces grow by between 1.25 (upright
  // ones) and 1.25^2 (level ones), and by at most 7% more in the ramps
  // (tilted by up to 0.25 / 0.1 x their 15 cm from the axis).
  const double lo = m.crotch + 0.06, hi = m.waist - 0.10, ramp = 0.1;
  ASSERT_GT(hi - lo, 0.06);
  const geometry::Points grown = swollen(body, lo, hi, 1.25, ramp);
  const EaseProfile room = hip_room(body, {body.mesh.vertices, grown}, 0.08);
  const double give = 1.08 * 1.08, low = 0.5 * (m.crotch + m.knee);
  double shortest = 1e9, longest = 0.0;
  for (double y = m.waist; y > low; y -= 0.02) {
    shortest = std::min(shortest, outline(body.mesh.vertices, y));
    longest = std::max(longest, outline(body.mesh.vertices, y));
  }
  // One value over the whole region: what its most grown band asks for.
  const double mid = nearest_knot(room, 0.5 * (lo + hi));
  EXPECT_GT(room(mid), (1.0 + kLegRoomMargin) * shortest * (1.25 / give - 1.0) / (2 * M_PI));
  EXPECT_LT(room(mid), (1.0 + kLegRoomMargin) * longest * (1.25 * 1.25 * 1.07 / give - 1.0) / (2 * M_PI));
  for (double y = m.waist - 0.01; y > low + 0.01; y -= 0.02) EXPECT_NEAR(room(y), room(mid), 1e-12) << "at " << y;
  // Nothing beyond the region: above the waist, below mid-thigh.
  EXPECT_EQ(room(m.waist + 0.05), 0.0);
  EXPECT_EQ(room(low - 0.05), 0.0);
  // Cloth that gives 30% covers what grew (at most 1.25^2 x 1.07 < 1.3^2).
  const EaseProfile covered = hip_room(body, {body.mesh.vertices, grown}, 0.3);
  for (const auto& [h, e] : covered.knots) EXPECT_NEAR(e, 0.0, 1e-9) << "at height " << h;
}

TEST(GarmentHipRoom, PantsGetLooserAtTheSeatAndKeepTheirCrotch) {
  const TPoseBody& body = test::tpose(0);
  const Landmarks m = measure(body);
  MotionRoom room;
  room.hips = EaseProfile(0.04);
  const GarmentParams params = test::params_at(0.02);
  for (const char* type : {"pants", "jumpsuit"}) {
    SCOPED_TRACE(type);
    const GarmentMesh plain = build_garment(type, body, params, 5);
    const GarmentMesh roomy = build_garment(type, body, params, 5, {}, &room);
    // 4 cm of ease all round the hips is 2 pi x (4 cm - the garment's own) longer.
    EXPECT_GT(outline(roomy.vertices, m.hip, 0.01), outline(plain.vertices, m.hip, 0.01) + 0.1);
    // The crotch stays where the garment's own ease puts it.
    const double low = m.knee;
    EXPECT_NEAR(crotch_of(roomy, low), crotch_of(plain, low), 0.01);
    // Below the crotch the legs stay apart: no vertex of one leg crosses the midline.
    const double crotch = crotch_of(plain, low);
    for (int v = 0; v < roomy.vertices.rows(); ++v) {
      if (roomy.vertices(v, 1) >= crotch - 0.03) continue;
      ASSERT_GT(std::abs(roomy.vertices(v, 0)), 0.002) << "vertex " << v;
    }
  }
}

}  // namespace
}  // namespace layers::garment
