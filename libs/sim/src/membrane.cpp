// Membrane energy terms for projective dynamics (see projective.h): the
// matrix part and the local projections of the warp/weft axes and of their
// angle.
#include <array>
#include <cmath>

#include "projective.h"

namespace layers::sim::detail {

namespace {

// w * (a a^T) for the three corners into the triplet list.
void add_outer(const MembraneElement& e, const std::array<double, 3>& a, double w, Triplets& out) {
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) out.emplace_back(e.v[i], e.v[j], w * a[i] * a[j]);
}

Vec3 axis(const MembraneElement& e, const std::array<double, 3>& w, const Vec3s& x) {
  return w[0] * x[e.v[0]] + w[1] * x[e.v[1]] + w[2] * x[e.v[2]];
}

// Closest pair (a, b) with a . b = 0 to (a0, b0): a = (a0 - l b0)/(1 - l^2),
// b = (b0 - l a0)/(1 - l^2), l the small root of d l^2 - S l + d = 0.
bool orthogonalise(const Vec3& a0, const Vec3& b0, Vec3& a, Vec3& b) {
  const double d = a0.dot(b0), s = a0.squaredNorm() + b0.squaredNorm();
  const double root = std::sqrt(std::max(0.0, s * s - 4 * d * d));
  if (!(s + root > 0)) return false;
  const double l = 2 * d / (s + root);
  const double q = 1 - l * l;
  if (!(q > 1e-6)) return false;
  a = (a0 - l * b0) / q;
  b = (b0 - l * a0) / q;
  return true;
}

}  // namespace

void add_membrane_matrix(const Cloth& cloth, Triplets& out) {
  const Material& m = cloth.material();
  for (const MembraneElement& e : cloth.membrane()) {
    const double axis_weight = (m.tension_modulus + m.compression_modulus) * e.area;
    const double shear_weight = 2 * m.shear_modulus * e.area;
    add_outer(e, e.wu, axis_weight + shear_weight, out);
    add_outer(e, e.wv, axis_weight + shear_weight, out);
  }
}

void add_membrane_projections(const Cloth& cloth, const Vec3s& x, Vec3s& rhs) {
  const Material& m = cloth.material();
  for (const MembraneElement& e : cloth.membrane()) {
    const Vec3 fu = axis(e, e.wu, x), fv = axis(e, e.wv, x);
    // Stretch: the tension target caps an axis' length at 1, the
    // compression target raises it to 1; each leaves it alone on its free
    // side. Weighted targets of the u and v terms are summed, then
    // scattered once.
    const double et = m.tension_modulus * e.area, ec = m.compression_modulus * e.area;
    const auto stretch = [&](const Vec3& f) {
      const double len = f.norm();
      if (!(len > 0)) return Vec3((et + ec) * f);
      return Vec3((len > 1 ? et / len + ec : et + ec / len) * f);
    };
    Vec3 pu = stretch(fu), pv = stretch(fv);
    if (m.shear_modulus > 0) {
      Vec3 a = fu, b = fv;
      if (!orthogonalise(fu, fv, a, b)) {
        a = fu;
        b = fv;
      }
      const double w = 2 * m.shear_modulus * e.area;
      pu += w * a;
      pv += w * b;
    }
    for (int k = 0; k < 3; ++k) rhs[e.v[k]] += e.wu[k] * pu + e.wv[k] * pv;
  }
}

}  // namespace layers::sim::detail
