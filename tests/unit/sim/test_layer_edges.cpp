// Edge-edge contact between layers (internal EdgeContact): an outer edge
// that passes through an inner edge within a substep is put back on the
// side it started on, a thickness away; edges farther apart and vertices
// held by the body do not move.
#include <gtest/gtest.h>

#include "cloth_contact.h"
#include "fixtures.h"
#include "layers/sim/cloth.h"

namespace layers::sim {
namespace {

using test::V3;

// One triangle whose first edge runs from a to b, its third vertex 5 cm
// off along `side`.
Cloth triangle(const V3& a, const V3& b, const V3& side) {
  return Cloth(test::make_mesh({a, b, 0.5 * (a + b) + 0.05 * side}, {{0, 1, 2}}), Material{});
}

// The edge a-b of `state` moved by `by` (start positions stay).
void move_edge(Cloth::State& state, const V3& by) {
  state.x[0] += by;
  state.x[1] += by;
}

// Meets every outer edge with every inner one (the solver lists the pairs
// from its candidates).
double collide(const Cloth& inner, Cloth::State& in, const std::vector<double>& w_in, const Cloth& outer,
               Cloth::State& out, double thickness, Vec3s& in_push, Vec3s& out_push) {
  const detail::EdgeContact::Side i{&inner.edges(), &in.x_start, &in.x, nullptr, &w_in, &in_push};
  const detail::EdgeContact::Side o{&outer.edges(), &out.x_start, &out.x, nullptr, &out.inv_mass, &out_push};
  std::vector<std::array<int, 2>> pairs;
  for (int k = 0; k < outer.edges().rows(); ++k)
    for (int e = 0; e < inner.edges().rows(); ++e) pairs.push_back({k, e});
  return detail::EdgeContact::collide(i, o, thickness, pairs);
}

TEST(LayerEdges, AnEdgeThatPassedThroughIsPutBack) {
  // Inner edge along x; outer edge along z, 2 mm above it, then moved 5 mm
  // down: through the inner edge, with neither triangle's vertices near the
  // other triangle (vertex-triangle contact cannot see it).
  const Cloth inner = triangle(V3(-0.05, 0, 0), V3(0.05, 0, 0), V3(0, -1, 0));
  const Cloth outer = triangle(V3(0.01, 0.002, -0.05), V3(0.01, 0.002, 0.05), V3(0, 1, 0));
  Cloth::State in = inner.state(), out = outer.state();
  move_edge(out, V3(0, -0.005, 0));
  Vec3s in_push(3, Vec3::Zero()), out_push(3, Vec3::Zero());
  collide(inner, in, in.inv_mass, outer, out, 0.004, in_push, out_push);
  // The closest points (the middle of the outer edge, 60% along the inner
  // one) are back 4 mm apart, the outer one above: both sides moved along y.
  const double above = 0.5 * (out.x[0].y() + out.x[1].y());
  const double below = 0.4 * in.x[0].y() + 0.6 * in.x[1].y();
  EXPECT_NEAR(above - below, 0.004, 1e-9);
  EXPECT_GT(out_push[0].y(), 0.0);
  EXPECT_LT(in_push[0].y(), 0.0);
  EXPECT_NEAR(out.x[0].y(), -0.003 + out_push[0].y(), 1e-9);  // (float rest positions)
  EXPECT_NEAR(out_push[0].x(), 0.0, 1e-12);
  EXPECT_DOUBLE_EQ(in.x[2].y(), inner.state().x[2].y());  // the third vertices are not on the edges
}

TEST(LayerEdges, HeldInnerVerticesStayAndEdgesApartAreLeftAlone) {
  const Cloth inner = triangle(V3(-0.05, 0, 0), V3(0.05, 0, 0), V3(0, -1, 0));
  const Cloth outer = triangle(V3(0.01, 0.002, -0.05), V3(0.01, 0.002, 0.05), V3(0, 1, 0));
  Cloth::State in = inner.state(), out = outer.state();
  move_edge(out, V3(0, -0.005, 0));
  std::vector<double> held(3, 0.0);  // all inner vertices held by the body
  Vec3s in_push(3, Vec3::Zero()), out_push(3, Vec3::Zero());
  collide(inner, in, held, outer, out, 0.004, in_push, out_push);
  EXPECT_EQ(in.x[0], inner.state().x[0]);
  EXPECT_EQ(in.x[1], inner.state().x[1]);
  EXPECT_NEAR(out.x[0].y(), 0.004, 1e-9);

  // 6 mm apart and staying so: nothing moves.
  Cloth::State far_in = inner.state(), far_out = outer.state();
  move_edge(far_out, V3(0, 0.004, 0));
  far_out.x_start = far_out.x;
  const Vec3s before = far_out.x;
  collide(inner, far_in, far_in.inv_mass, outer, far_out, 0.004, in_push, out_push);
  EXPECT_EQ(far_out.x, before);
  EXPECT_EQ(far_in.x, inner.state().x);
}

}  // namespace
}  // namespace layers::sim
