// Pareto front of accuracy against speed (see pareto.h).
#include "layers/report/pareto.h"

#include <algorithm>
#include <cmath>

namespace layers::report {
namespace {

bool eligible(const ParetoPoint& p) { return std::isfinite(p.cost) && std::isfinite(p.error) && p.cost > 0; }

bool dominates(const ParetoPoint& a, const ParetoPoint& b) {
  return a.cost <= b.cost && a.error <= b.error && (a.cost < b.cost || a.error < b.error);
}

}  // namespace

std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points) {
  std::vector<bool> on(points.size(), false);
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (!eligible(points[i])) continue;
    on[i] = std::none_of(points.begin(), points.end(),
                         [&](const ParetoPoint& other) { return eligible(other) && dominates(other, points[i]); });
  }
  return on;
}

std::vector<std::size_t> pareto_order(const std::vector<ParetoPoint>& points) {
  const std::vector<bool> on = pareto_front(points);
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < points.size(); ++i)
    if (on[i]) order.push_back(i);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (points[a].cost != points[b].cost) return points[a].cost < points[b].cost;
    return points[a].error < points[b].error;
  });
  return order;
}

}  // namespace layers::report
