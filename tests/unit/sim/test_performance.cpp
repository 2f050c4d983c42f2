// The performance-like case: an inner and an outer garment (about 5k
// vertices together) on a ~13k-vertex body that sways, with wind. Prints
// ms per frame (wall clock and CPU time) and where the time goes; never
// asserts on time. Also checks that the case stays valid.
#include <gtest/gtest.h>

#include <cstdio>
#include <ctime>

#include "scenes.h"

namespace layers::sim {
namespace {

using geometry::Points;

TEST(Performance, TwoLayersOnAMovingBody) {
  test::DressedCapsule scene;
  scene.two_layers = true;
  scene.body_edge = 0.0085;
  scene.edge = 0.0175;
  // A dress under a shorter jacket, as in the paper's L splits.
  scene.inner_length = 0.62;
  scene.outer_length = 0.5;
  scene.outer_radius = 0.175;
  Solver s = scene.make();
  const Points rest = s.body().vertices;
  std::printf("[sim] perf case: body %d vertices, garments %d vertices (%d + %d), %d substeps x %d iterations\n",
              static_cast<int>(rest.rows()), test::garment_vertices(s), s.cloth(0).num_vertices(),
              s.cloth(1).num_vertices(), s.config().substeps, s.config().iterations);
  for (int f = 0; f < 15; ++f) s.step();  // settle
  SequenceMeasures measures;
  s.reset_timings();
  Wind wind;
  wind.direction = test::V3(1, 0, 0);
  wind.strength = 300;
  const int frames = 45;
  double cpu = 0;
  for (int f = 1; f <= frames; ++f) {
    const Points next = test::sway(rest, f);
    const std::clock_t start = std::clock();
    s.step(next, f > 15 ? wind : Wind{});
    cpu += static_cast<double>(std::clock() - start) / CLOCKS_PER_SEC;
    measures.add(measure_frame(s));
  }
  const StepTimings& t = s.timings();
  const auto part = [&](double seconds) { return 1000 * seconds / t.frames; };
  std::printf(
      "[sim] perf case: %.1f ms/frame CPU on one thread, %.1f ms wall (predict+wind %.1f, elastic %.1f, "
      "layers %.1f, self %.1f, body %.1f, strain cap %.1f)\n",
      1000 * cpu / frames, part(t.total), part(t.predict), part(t.elastic), part(t.layer_contact), part(t.self_contact),
      part(t.body_contact), part(t.strain_cap));
  std::printf("[sim] perf case: mean H-penetration %.3f%%, mean L-penetration %.3f%%, max stretch %.1f%%\n",
              100 * measures.mean_h_penetration(), 100 * measures.mean_l_penetration(), 100 * measures.max_stretch());
  EXPECT_EQ(measures.nonfinite(), 0);
  EXPECT_LT(measures.mean_h_penetration(), 0.005);
  EXPECT_LT(measures.mean_l_penetration(), 0.005);
  EXPECT_LT(measures.max_stretch(), 0.10);  // the validation threshold (the cap holds at ~8.5%)
}

}  // namespace
}  // namespace layers::sim
