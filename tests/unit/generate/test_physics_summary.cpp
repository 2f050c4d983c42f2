// The summary under `layers validate --physics`'s table: the spread of each
// per-sequence measure over sequences (NaN left out) and the frames and
// sequences within the crossing target, on hand-made frame measures.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "layers/core/error.h"
#include "layers/generate/physics_summary.h"

namespace layers::generate {
namespace {

sim::FrameMeasures frame(double h_crossing, double l_crossing) {
  sim::FrameMeasures f;
  f.h_crossing = h_crossing;
  f.l_crossing = l_crossing;
  return f;
}

TEST(PhysicsSummary, SpreadLeavesNaNOutAndUsesNearestRank) {
  std::vector<double> v;
  for (int i = 10; i >= 1; --i) v.push_back(i);
  v.push_back(std::nan(""));
  const Spread s = spread_of(v);
  EXPECT_EQ(s.count, 10);
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.p10, 1);
  EXPECT_EQ(s.median, 5);
  EXPECT_EQ(s.p90, 9);
  EXPECT_EQ(s.max, 10);
  const Spread none = spread_of({std::nan("")});
  EXPECT_EQ(none.count, 0);
  EXPECT_EQ(none.max, 0);
}

TEST(PhysicsSummary, CountsFramesAndSequencesWithinTheTarget) {
  PhysicsSummary summary(0.001);
  // Sequence 1: every frame within (the target itself counts as within).
  summary.add_frame(frame(0.0, 0.0));
  summary.add_frame(frame(0.001, 0.0005));
  summary.end_sequence({{"H-x mean", 0.0005}, {"stretch", 0.085}});
  // Sequence 2: one frame over on H, one over on L, one unmeasurable.
  summary.add_frame(frame(0.002, 0.0));
  summary.add_frame(frame(0.0, 0.02));
  summary.add_frame(frame(std::nan(""), 0.0));
  summary.add_frame(frame(0.0, 0.0));
  summary.end_sequence({{"H-x mean", 0.004}, {"stretch", 0.09}});
  EXPECT_EQ(summary.frames(), 6);
  EXPECT_EQ(summary.frames_h_within(), 4);
  EXPECT_EQ(summary.frames_l_within(), 5);
  EXPECT_EQ(summary.frames_both_within(), 3);
  EXPECT_EQ(summary.sequences(), 2);
  EXPECT_EQ(summary.sequences_within(), 1);
  EXPECT_EQ(summary.spread("stretch").max, 0.09);
  EXPECT_EQ(summary.spread("H-x mean").min, 0.0005);
  const std::string text = summary.text();
  EXPECT_NE(text.find("spread over 2 sequences"), std::string::npos) << text;
  EXPECT_NE(text.find("both 3 (50.0%)"), std::string::npos) << text;
  EXPECT_NE(text.find("every frame: 1 of 2"), std::string::npos) << text;
  EXPECT_THROW(summary.spread("L-x mean"), Error);
  // Every sequence must give the same columns; a refused one records nothing.
  EXPECT_THROW(summary.end_sequence({{"H-x mean", 0.0}, {"H-x max", 0.1}}), Error);
  EXPECT_EQ(summary.sequences(), 2);
  EXPECT_EQ(summary.spread("H-x mean").count, 2);
}

}  // namespace
}  // namespace layers::generate
