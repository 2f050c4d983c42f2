// The Pareto front of accuracy against speed on hand-made points.
#include <gtest/gtest.h>

#include <cmath>

#include "layers/report/pareto.h"

namespace layers::report {
namespace {

TEST(Pareto, DominatedPointsLeaveTheFront) {
  // a: fast and poor, b: slow and good, c: slower and worse than b, d: between a and b.
  const std::vector<ParetoPoint> p = {{1, 20}, {10, 5}, {12, 6}, {3, 10}, {4, 12}};
  EXPECT_EQ(pareto_front(p), (std::vector<bool>{true, true, false, true, false}));
  EXPECT_EQ(pareto_order(p), (std::vector<std::size_t>{0, 3, 1}));
}

TEST(Pareto, TiesAndEqualCoordinates) {
  // Two identical points both stay; same speed but worse error, or same
  // error but slower, is dominated.
  const std::vector<ParetoPoint> p = {{2, 8}, {2, 8}, {2, 9}, {5, 8}, {1, 30}};
  EXPECT_EQ(pareto_front(p), (std::vector<bool>{true, true, false, false, true}));
  EXPECT_EQ(pareto_order(p), (std::vector<std::size_t>{4, 0, 1}));
}

TEST(Pareto, UnmeasuredPointsAreNeitherOnTheFrontNorDominating) {
  const double nan = std::nan("");
  // The zero-cost and NaN points would dominate everything if they counted.
  const std::vector<ParetoPoint> p = {{0, 1}, {nan, 1}, {3, nan}, {4, 9}, {-1, 0}};
  EXPECT_EQ(pareto_front(p), (std::vector<bool>{false, false, false, true, false}));
  EXPECT_TRUE(pareto_front({}).empty());
  EXPECT_EQ(pareto_order({{7, 3}}), (std::vector<std::size_t>{0}));
}

}  // namespace
}  // namespace layers::report
