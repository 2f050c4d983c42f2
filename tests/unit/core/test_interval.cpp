// The 95% interval of a mean and of paired differences, against values
// worked by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

#include "layers/core/interval.h"

namespace layers {
namespace {

TEST(Interval, CriticalValuesFromTheTableAndBeyond) {
  EXPECT_DOUBLE_EQ(t_critical_95(1), 12.706);
  EXPECT_DOUBLE_EQ(t_critical_95(19), 2.093);
  EXPECT_NEAR(t_critical_95(40), 2.021, 1e-3);
  EXPECT_NEAR(t_critical_95(120), 1.980, 1e-3);
  EXPECT_NEAR(t_critical_95(100000), 1.960, 1e-3);
  EXPECT_TRUE(std::isnan(t_critical_95(0)));
}

TEST(Interval, MeanSampleDeviationAndHalfWidth) {
  // 1..5: mean 3, sample sd sqrt(2.5), half-width 2.776 * sqrt(2.5 / 5).
  const MeanInterval m = mean_interval({1, 2, 3, 4, 5});
  EXPECT_EQ(m.n, 5u);
  EXPECT_DOUBLE_EQ(m.mean, 3);
  EXPECT_DOUBLE_EQ(m.sd, std::sqrt(2.5));
  EXPECT_NEAR(m.half_width, 2.776 * std::sqrt(0.5), 1e-12);
  EXPECT_TRUE(m.above_zero());
  EXPECT_FALSE(m.below_zero());
}

TEST(Interval, NonFiniteLeftOutAndTooFewValues) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const MeanInterval one = mean_interval({nan, 4.0});
  EXPECT_EQ(one.n, 1u);
  EXPECT_DOUBLE_EQ(one.mean, 4);
  EXPECT_TRUE(std::isnan(one.half_width));
  EXPECT_FALSE(one.above_zero());
  EXPECT_TRUE(std::isnan(mean_interval({}).mean));
}

TEST(Interval, PairedDifferencesSkipIncompletePairs) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  // Differences 1, 1, 2 (the NaN pair left out): mean 4/3.
  const MeanInterval d = paired_interval({2, 3, 5, nan}, {1, 2, 3, 0});
  EXPECT_EQ(d.n, 3u);
  EXPECT_DOUBLE_EQ(d.mean, 4.0 / 3);
  // Half-width 4.303 * sd(1, 1, 2) / sqrt(3) = 1.43: the interval spans 0.
  EXPECT_NEAR(d.half_width, 4.303 * std::sqrt(1.0 / 3) / std::sqrt(3.0), 1e-12);
  EXPECT_FALSE(d.above_zero());
  EXPECT_THROW(paired_interval({1}, {1, 2}), std::invalid_argument);
}

TEST(Interval, StudentPValuesWorkedByHand) {
  // df 1 is the Cauchy law: P(|T| >= 1) = 1/2. df 2: P(|T| >= t) = 1 - t / sqrt(2 + t^2).
  EXPECT_NEAR(t_two_sided_p(1.0, 1), 0.5, 1e-12);
  EXPECT_NEAR(t_two_sided_p(-1.0, 2), 1 - 1 / std::sqrt(3.0), 1e-12);
  EXPECT_NEAR(t_two_sided_p(0.0, 7), 1.0, 1e-12);
  // The table's critical values sit at p = 0.05 (to their 3 decimals);
  // a fractional df lies between its neighbours.
  EXPECT_NEAR(t_two_sided_p(2.776, 4), 0.05, 1e-4);
  EXPECT_NEAR(t_two_sided_p(12.706, 1), 0.05, 1e-4);
  EXPECT_NEAR(t_two_sided_p(2.042, 30), 0.05, 1e-4);
  const double between = t_two_sided_p(2.5, 4.5);
  EXPECT_LT(t_two_sided_p(2.5, 5), between);
  EXPECT_GT(t_two_sided_p(2.5, 4), between);
  EXPECT_TRUE(std::isnan(t_two_sided_p(1.0, 0)));
  EXPECT_TRUE(std::isnan(t_two_sided_p(std::numeric_limits<double>::quiet_NaN(), 3)));
}

TEST(Interval, HolmStepsDownAndStopsAtTheFirstKept) {
  // Sorted: 0.005 <= 0.05/4, 0.01 <= 0.05/3, 0.03 > 0.05/2: stop; 0.04 is
  // kept although it is below 0.05.
  const std::vector<bool> r = holm_rejects({0.01, 0.04, 0.03, 0.005});
  EXPECT_EQ(r, (std::vector<bool>{true, false, false, true}));
  // A NaN counts in m but is never rejected: 0.001 <= 0.05/3, then
  // 0.03 > 0.05/2 (with m = 2, 0.03 would still be above 0.05/2; 0.02 below).
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(holm_rejects({nan, 0.03, 0.001}), (std::vector<bool>{false, false, true}));
  EXPECT_EQ(holm_rejects({nan, 0.02, 0.001}), (std::vector<bool>{false, true, true}));
  EXPECT_TRUE(holm_rejects({}).empty());
}

}  // namespace
}  // namespace layers
