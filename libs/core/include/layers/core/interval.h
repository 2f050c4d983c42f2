// layers/core/interval.h -- the one 95% confidence interval of the
// toolkit: the mean of n values (per sequence, per scene) with the
// Student t half-width over the sample standard deviation (n - 1). A
// paired comparison is the interval of the per-item differences. Also the
// Student t p-value and Holm's step-down rule, for reading many
// comparisons at once.
#pragma once

#include <cstddef>
#include <vector>

namespace layers {

struct MeanInterval {
  std::size_t n = 0;
  double mean = 0;        // NaN when n == 0
  double sd = 0;          // sample standard deviation; NaN when n < 2
  double half_width = 0;  // t(0.975, n - 1) * sd / sqrt(n); NaN when n < 2
  double low() const { return mean - half_width; }
  double high() const { return mean + half_width; }
  // True when the whole interval lies above (below) zero.
  bool above_zero() const { return n >= 2 && low() > 0; }
  bool below_zero() const { return n >= 2 && high() < 0; }
};

// The two-sided 95% Student t critical value for `df` degrees of freedom
// (exact to 3 decimals up to 30, then the Cornish-Fisher expansion).
double t_critical_95(std::size_t df);

// Non-finite values are left out (n counts the finite ones).
MeanInterval mean_interval(const std::vector<double>& values);

// The interval of a[i] - b[i] over the items where both are finite
// (sizes must agree: std::invalid_argument otherwise).
MeanInterval paired_interval(const std::vector<double>& a, const std::vector<double>& b);

// Two-sided p-value of a Student t statistic `t` with `df` degrees of
// freedom (df may be fractional: Satterthwaite's); NaN for df <= 0 or a
// non-finite t.
double t_two_sided_p(double t, double df);

// Holm's step-down rule at level `alpha` over the p-values of one family of
// comparisons: true where that comparison's null is rejected (the k-th
// smallest p against alpha / (m - k + 1), stopping at the first that is
// not). NaN p-values are never rejected and count in m.
std::vector<bool> holm_rejects(const std::vector<double>& p, double alpha = 0.05);

}  // namespace layers
