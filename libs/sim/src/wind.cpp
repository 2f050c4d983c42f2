// Wind: quaternion conversions, the span schedule and the face pressure
// forces (see wind.h).
#include "layers/sim/wind.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "layers/core/error.h"

namespace layers::sim {

Wind Wind::from_rotation(const Eigen::Vector4d& q_in, double strength) {
  const double n = q_in.norm();
  if (!(n > 0) || !std::isfinite(n)) {
    throw InputError("wind", "rotation", "a non-zero finite quaternion (w, x, y, z)", "zero or non-finite");
  }
  const Eigen::Vector4d q = q_in / n;
  const double w = q[0], x = q[1], y = q[2], z = q[3];
  Wind out;
  // Third column of the rotation matrix: R * (0, 0, 1).
  out.direction = Vec3(2 * (x * z + w * y), 2 * (y * z - w * x), 1 - 2 * (x * x + y * y)).normalized();
  out.strength = strength;
  return out;
}

Eigen::Vector4d Wind::rotation() const {
  const Vec3 from(0, 0, 1);
  const Vec3 to = direction.normalized();
  const double c = from.dot(to);
  if (c < -1 + 1e-12) return {0, 1, 0, 0};  // half turn about x
  const Vec3 axis = from.cross(to);
  Eigen::Vector4d q(1 + c, axis.x(), axis.y(), axis.z());
  return q / q.norm();
}

WindSchedule::WindSchedule(std::vector<WindSpan> spans) : spans_(std::move(spans)) {
  std::sort(spans_.begin(), spans_.end(), [](const WindSpan& a, const WindSpan& b) { return a.begin < b.begin; });
  for (std::size_t i = 0; i < spans_.size(); ++i) {
    const WindSpan& s = spans_[i];
    const std::string where = "span [" + std::to_string(s.begin) + ", " + std::to_string(s.end) + ")";
    if (s.end <= s.begin) throw InputError("wind", where, "begin < end", "an empty or reversed span");
    if (std::abs(s.wind.direction.norm() - 1) > 1e-3) {
      throw InputError("wind", where + " direction", "a unit vector",
                       "length " + std::to_string(s.wind.direction.norm()));
    }
    if (!(s.wind.strength >= 0) || !std::isfinite(s.wind.strength)) {
      throw InputError("wind", where + " strength", "a number >= 0", std::to_string(s.wind.strength));
    }
    if (i > 0 && s.begin < spans_[i - 1].end) {
      throw InputError(
          "wind", where, "spans that do not overlap",
          "overlap with [" + std::to_string(spans_[i - 1].begin) + ", " + std::to_string(spans_[i - 1].end) + ")");
    }
  }
}

Wind WindSchedule::at(int frame) const {
  for (const WindSpan& s : spans_) {
    if (frame >= s.begin && frame < s.end) return s.wind;
  }
  Wind calm;
  calm.strength = 0;
  return calm;
}

void add_wind_forces(const std::vector<std::array<int, 3>>& faces, const Vec3s& x, const Wind& wind,
                     double pressure_per_strength, Vec3s& forces) {
  const double pressure = pressure_per_strength * wind.strength;
  if (pressure == 0.0) return;
  const Vec3 w = wind.direction;
  for (const auto& f : faces) {
    // Area-weighted normal: a = 2 A n.
    const Vec3 a = (x[f[1]] - x[f[0]]).cross(x[f[2]] - x[f[0]]);
    const double len = a.norm();
    if (len == 0.0) continue;
    // P A (n.w) n = P (a.w) a / (2 |a|); a third per corner.
    const Vec3 per_corner = (pressure * a.dot(w) / (6.0 * len)) * a;
    for (int k = 0; k < 3; ++k) forces[f[k]] += per_corner;
  }
}

}  // namespace layers::sim
