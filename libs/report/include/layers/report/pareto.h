// layers/report/pareto.h -- the Pareto front of accuracy against speed.
//
// A point is on the front when no other point is at least as fast and at
// least as accurate while strictly better in one of the two (lower cost
// and lower error are better). Identical points are all on the front; a
// point as fast as another but less accurate (or as accurate but slower)
// is not. Points with a non-finite coordinate or a cost <= 0 (speed not
// measured) are never on the front and dominate nothing.
#pragma once

#include <cstddef>
#include <vector>

namespace layers::report {

struct ParetoPoint {
  double cost = 0;   // ms per frame
  double error = 0;  // mm
};

// on_front[i] tells whether points[i] is on the front.
std::vector<bool> pareto_front(const std::vector<ParetoPoint>& points);

// Indices of the front's points, fastest first (ties: lower error first,
// then input order).
std::vector<std::size_t> pareto_order(const std::vector<ParetoPoint>& points);

}  // namespace layers::report
