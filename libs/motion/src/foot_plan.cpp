// Foot trajectories between planted stances (see foot_plan.h).
#include "foot_plan.h"

#include <algorithm>
#include <cmath>

namespace layers::motion {

double bump(double s) {
  s = std::clamp(s, 0.0, 1.0);
  return 16.0 * s * s * (1.0 - s) * (1.0 - s);
}

namespace {

// How much of a full step the move from a to b is (0..1).
double step_size(const Stance& a, const Stance& b, const SwingStyle& style) {
  const double d = (b.ball - a.ball).norm();
  const double turn = std::abs(b.yaw - a.yaw);
  return std::clamp(std::max({d / style.full_step, turn / 0.6, b.min_lift}), 0.0, 1.0);
}

}  // namespace

FootState foot_at(const std::vector<Stance>& plan, double t, const SwingStyle& style) {
  FootState f;
  if (plan.empty()) return f;
  if (t <= plan.front().start) {
    f.ball = plan.front().ball;
    f.yaw = plan.front().yaw;
    return f;
  }
  for (std::size_t k = 0; k < plan.size(); ++k) {
    const Stance& s = plan[k];
    if (t <= s.end) {
      if (t >= s.start) {
        // Planted; the heel rises over the end of the stance before a step.
        f.ball = s.ball;
        f.yaw = s.yaw;
        if (k + 1 < plan.size()) {
          const double size = step_size(s, plan[k + 1], style);
          const double share = std::min(style.heel_share * (s.end - s.start), style.heel_time);
          f.pitch = style.heel_off * size * body::smoothstep((t - (s.end - share)) / share);
          f.toe_bend = f.pitch;
        }
        return f;
      }
      // Swing from the previous stance to this one.
      const Stance& a = plan[k - 1];
      const double u = (t - a.end) / (s.start - a.end);
      const double size = step_size(a, s, style);
      const double w = body::smootherstep(u);
      f.ball = (1.0 - w) * a.ball + w * s.ball;
      f.ball.y() += style.clearance * size * bump(u);
      f.yaw = (1.0 - w) * a.yaw + w * s.yaw;
      f.planted = u > 0.6;  // about to land: the pelvis guard must let it reach
      const double toe_off = style.heel_off * size;
      f.pitch = toe_off * (1.0 - body::smoothstep(u / 0.7));
      f.toe_bend = toe_off * (1.0 - body::smoothstep(u / 0.3));
      return f;
    }
  }
  f.ball = plan.back().ball;
  f.yaw = plan.back().yaw;
  return f;
}

std::vector<Stance> plan_steps(const std::function<body::Vec3(double)>& position,
                               const std::function<double(double)>& yaw, double period, double duty, double phase,
                               double duration, const body::Vec3& offset, double toe_out) {
  std::vector<Stance> plan;
  for (int k = -2;; ++k) {
    Stance s;
    s.start = (k + phase) * period;
    s.end = s.start + duty * period;
    if (s.start > duration + period) break;
    const double mid = 0.5 * (s.start + s.end);
    const double heading = yaw(mid);
    s.ball = position(mid) + body::rot_y(heading) * offset;
    s.ball.y() = 0.0;
    s.yaw = heading + toe_out;
    plan.push_back(s);
  }
  return plan;
}

}  // namespace layers::motion
