// Rotation helpers (see rotation.h).
#include "layers/body/rotation.h"

#include <algorithm>
#include <cmath>

namespace layers::body {

Quat axis_angle(const Vec3& axis, double angle) {
  double n = axis.norm();
  if (n < 1e-15) return Quat::Identity();
  return Quat(Eigen::AngleAxisd(angle, axis / n));
}

Quat euler(const char order[3], const double angles[3]) {
  Quat q = Quat::Identity();
  for (int k = 0; k < 3; ++k) {
    Vec3 axis = Vec3::Zero();
    axis[order[k] - 'X'] = 1.0;
    q = q * axis_angle(axis, angles[k]);
  }
  return q;
}

Quat shortest_arc(const Vec3& from, const Vec3& to) {
  Quat q = Quat::FromTwoVectors(from, to);
  return q.normalized();
}

Quat aim(const Vec3& a1, const Vec3& a2, const Vec3& b1, const Vec3& b2) {
  auto frame = [](const Vec3& u, const Vec3& v) {
    Vec3 x = u.normalized();
    Vec3 z = x.cross(v).normalized();
    Vec3 y = z.cross(x);
    Mat3 m;
    m << x, y, z;
    return m;
  };
  Mat3 r = frame(b1, b2) * frame(a1, a2).transpose();
  return Quat(r).normalized();
}

Quat same_hemisphere(const Quat& q, const Quat& reference) {
  if (q.dot(reference) < 0) return Quat(-q.w(), -q.x(), -q.y(), -q.z());
  return q;
}

Quat slerp(const Quat& a, const Quat& b, double t) { return a.slerp(t, same_hemisphere(b, a)).normalized(); }

double angle_of(const Quat& q) {
  double w = std::min(1.0, std::abs(q.normalized().w()));
  return 2.0 * std::acos(w);
}

double smoothstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * (3.0 - 2.0 * x);
}

double smootherstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * x * (x * (6.0 * x - 15.0) + 10.0);
}

}  // namespace layers::body
