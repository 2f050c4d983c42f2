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

}  // namespace
}  // namespace layers
