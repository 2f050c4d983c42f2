// The fold cap over the cloth's hinges (see fold_limit.h).
#include "fold_limit.h"

#include <algorithm>
#include <cmath>

namespace layers::sim::detail {

// A hinge is corrected only when its wings are closer than the limit by
// more than this share of the squared distance (0.1% of the distance).
constexpr double kSlack = 2e-3;

namespace {

Vec3 rest_point(const Cloth& cloth, int v) { return cloth.rest_positions().row(v).cast<double>().transpose(); }

// The hinge's fold: the angle between the normals of (x0, x1, x2) and
// (x0, x3, x1), 0 when flat.
double fold_angle(const Vec3& x0, const Vec3& x1, const Vec3& x2, const Vec3& x3) {
  const Vec3 e = x1 - x0;
  const Vec3 n2 = e.cross(x2 - x0), n3 = (x3 - x0).cross(e);
  return std::atan2(n2.cross(n3).norm(), n2.dot(n3));
}

}  // namespace

void FoldLimiter::build(const Cloth& cloth, double max_fold) {
  const std::vector<BendingElement>& hinges = cloth.bending();
  cos_limit_.assign(hinges.size(), 0.0);
  for (std::size_t i = 0; i < hinges.size(); ++i) {
    const BendingElement& b = hinges[i];
    const double rest = fold_angle(rest_point(cloth, b.v[0]), rest_point(cloth, b.v[1]), rest_point(cloth, b.v[2]),
                                   rest_point(cloth, b.v[3]));
    cos_limit_[i] = std::cos(std::max(max_fold, rest));
  }
  revision_ = cloth.revision();
  max_fold_ = max_fold;
}

int FoldLimiter::apply(const Cloth& cloth, Cloth::State& s, double max_fold, int sweeps) {
  if (revision_ != cloth.revision() || max_fold_ != max_fold) build(cloth, max_fold);
  const std::vector<BendingElement>& hinges = cloth.bending();
  int sweep = 0;
  converged_ = false;
  while (sweep < sweeps && !converged_) {
    ++sweep;
    int corrected = 0;
    for (std::size_t i = 0; i < hinges.size(); ++i) {
      const BendingElement& hinge = hinges[i];
      const int a = hinge.v[2], b = hinge.v[3];
      const double wa = s.inv_mass[a], wb = s.inv_mass[b];
      if (wa + wb == 0.0) continue;
      // Seen along the hinge line, the wings' offsets from it (ha, hb long)
      // are an angle pi - f apart when the normals are f apart, so the
      // wings' distance across the line is
      // |pa - pb|^2 = ha^2 + hb^2 + 2 ha hb cos(f): it shrinks monotonically
      // as the fold sharpens. Only that component is corrected; their
      // offset along the line has nothing to do with the fold.
      const Vec3& x0 = s.x[hinge.v[0]];
      const Vec3 edge = s.x[hinge.v[1]] - x0;
      const Vec3 ra = s.x[a] - x0, rb = s.x[b] - x0;
      const double edge2 = edge.squaredNorm();
      if (!(edge2 > 1e-12 * (ra.squaredNorm() + rb.squaredNorm()))) continue;  // a collapsed hinge: no line
      const Vec3 axis = edge / std::sqrt(edge2);
      const Vec3 pa = ra - ra.dot(axis) * axis, pb = rb - rb.dot(axis) * axis;
      const double ha = pa.norm(), hb = pb.norm();
      const double limit2 = ha * ha + hb * hb + 2 * ha * hb * cos_limit_[i];
      const Vec3 d = pb - pa;
      const double len2 = d.squaredNorm();
      // Wings on top of each other have no direction to part in; the
      // hinge's neighbours move them apart first.
      if (len2 >= limit2 * (1 - kSlack) || len2 < 1e-18 * limit2) continue;
      const double len = std::sqrt(len2);
      const Vec3 correction = ((std::sqrt(limit2) - len) / (len * (wa + wb))) * d;
      s.x[a] -= wa * correction;
      s.x[b] += wb * correction;
      ++corrected;
    }
    converged_ = corrected == 0;
  }
  return sweep;
}

}  // namespace layers::sim::detail
