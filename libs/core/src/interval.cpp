// 95% intervals of a mean and of paired differences (see interval.h).
#include "layers/core/interval.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace layers {

double t_critical_95(std::size_t df) {
  static const double table[] = {0,     12.706, 4.303, 3.182, 2.776, 2.571, 2.447, 2.365, 2.306, 2.262, 2.228,
                                 2.201, 2.179,  2.160, 2.145, 2.131, 2.120, 2.110, 2.101, 2.093, 2.086, 2.080,
                                 2.074, 2.069,  2.064, 2.060, 2.056, 2.052, 2.048, 2.045, 2.042};
  if (df == 0) return std::numeric_limits<double>::quiet_NaN();
  if (df <= 30) return table[df];
  const double z = 1.959963984540054, n = static_cast<double>(df);
  const double z3 = z * z * z, z5 = z3 * z * z, z7 = z5 * z * z;
  return z + (z3 + z) / (4 * n) + (5 * z5 + 16 * z3 + 3 * z) / (96 * n * n) +
         (3 * z7 + 19 * z5 + 17 * z3 - 15 * z) / (384 * n * n * n);
}

MeanInterval mean_interval(const std::vector<double>& values) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  MeanInterval out;
  double sum = 0;
  for (double v : values)
    if (std::isfinite(v)) {
      sum += v;
      ++out.n;
    }
  out.mean = out.n ? sum / static_cast<double>(out.n) : kNaN;
  if (out.n < 2) {
    out.sd = out.half_width = kNaN;
    return out;
  }
  double ss = 0;
  for (double v : values)
    if (std::isfinite(v)) ss += (v - out.mean) * (v - out.mean);
  out.sd = std::sqrt(ss / static_cast<double>(out.n - 1));
  out.half_width = t_critical_95(out.n - 1) * out.sd / std::sqrt(static_cast<double>(out.n));
  return out;
}

MeanInterval paired_interval(const std::vector<double>& a, const std::vector<double>& b) {
  if (a.size() != b.size())
    throw std::invalid_argument("paired_interval: " + std::to_string(a.size()) + " against " +
                                std::to_string(b.size()) + " values");
  std::vector<double> d;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::isfinite(a[i]) && std::isfinite(b[i])) d.push_back(a[i] - b[i]);
  return mean_interval(d);
}

namespace {

// The continued fraction of the regularised incomplete beta function
// I_x(a, b), evaluated by the modified Lentz method (converges fast for
// x < (a + 1) / (a + b + 2); the caller uses the symmetry otherwise).
double beta_fraction(double a, double b, double x) {
  constexpr double kTiny = 1e-300;
  const auto guard = [](double v) { return std::fabs(v) < kTiny ? kTiny : v; };
  double c = 1, d = 1 / guard(1 - (a + b) * x / (a + 1)), f = d;
  for (int m = 1; m <= 300; ++m) {
    const double md = m;
    // Even step, then odd step of the fraction.
    double num = md * (b - md) * x / ((a + 2 * md - 1) * (a + 2 * md));
    d = 1 / guard(1 + num * d);
    c = guard(1 + num / c);
    f *= c * d;
    num = -(a + md) * (a + b + md) * x / ((a + 2 * md) * (a + 2 * md + 1));
    d = 1 / guard(1 + num * d);
    c = guard(1 + num / c);
    const double step = c * d;
    f *= step;
    if (std::fabs(step - 1) < 1e-15) break;
  }
  return f;
}

double incomplete_beta(double a, double b, double x) {
  if (x <= 0) return 0;
  if (x >= 1) return 1;
  const double front =
      std::exp(std::lgamma(a + b) - std::lgamma(a) - std::lgamma(b) + a * std::log(x) + b * std::log1p(-x));
  if (x < (a + 1) / (a + b + 2)) return front * beta_fraction(a, b, x) / a;
  return 1 - front * beta_fraction(b, a, 1 - x) / b;
}

}  // namespace

double t_two_sided_p(double t, double df) {
  if (!(df > 0) || !std::isfinite(t)) return std::numeric_limits<double>::quiet_NaN();
  // P(|T| >= |t|) = I_{df / (df + t^2)}(df / 2, 1 / 2).
  return incomplete_beta(df / 2, 0.5, df / (df + t * t));
}

std::vector<bool> holm_rejects(const std::vector<double>& p, double alpha) {
  std::vector<std::size_t> order(p.size());
  std::iota(order.begin(), order.end(), 0);
  const auto key = [&](std::size_t i) { return std::isnan(p[i]) ? std::numeric_limits<double>::infinity() : p[i]; };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return key(i) < key(j); });
  std::vector<bool> out(p.size(), false);
  const std::size_t m = p.size();
  for (std::size_t k = 0; k < m; ++k) {
    const double pk = p[order[k]];
    if (std::isnan(pk) || pk > alpha / static_cast<double>(m - k)) break;
    out[order[k]] = true;
  }
  return out;
}

}  // namespace layers
