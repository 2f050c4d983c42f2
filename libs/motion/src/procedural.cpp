// Procedural motions (see procedural.h): each kind fills per-frame
// PoseTargets (pelvis path, foot plans, spine, head and arm angles); a
// common pass lowers the pelvis smoothly where a leg could not reach its
// planted foot, then the PoseSolver turns targets into poses.
#include "layers/motion/procedural.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <random>

#include "foot_plan.h"
#include "layers/core/error.h"
#include "pose_solver.h"
#include "smoothing.h"

namespace layers::motion {
namespace {

constexpr double kPi = M_PI;
constexpr double kReach = 0.996;     // share of the leg length the pelvis guard allows
constexpr double kGuardSigma = 1.0;  // frames over which the guard's drop is spread

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : gen_(seed ^ 0x9E3779B97F4A7C15ull) {}
  double uniform(double a, double b) { return std::uniform_real_distribution<double>(a, b)(gen_); }
  double sign() { return uniform(0, 1) < 0.5 ? -1.0 : 1.0; }
  int pick(int n) { return std::uniform_int_distribution<int>(0, n - 1)(gen_); }

 private:
  std::mt19937_64 gen_;
};

// 0 -> 1 over [0, rise], holds, 1 -> 0 over [rise + hold, 2 rise + hold],
// then rests; u is the phase within the cycle, in [0, 1). C2.
double plateau(double u, double rise, double hold) {
  u -= std::floor(u);
  if (u < rise) return body::smootherstep(u / rise);
  if (u < rise + hold) return 1.0;
  return 1.0 - body::smootherstep((u - rise - hold) / rise);
}

// A pelvis path on the ground: integrated from a speed and a yaw rate.
class Path {
 public:
  Path(const std::function<double(double)>& speed, const std::function<double(double)>& yaw_rate, double duration)
      : t0_(-4.0), dt_(1.0 / 600.0) {
    const int n = static_cast<int>((duration + 8.0) / dt_) + 2;
    pos_.resize(n);
    yaw_.resize(n);
    pos_[0] = body::Vec3::Zero();
    yaw_[0] = 0.0;
    for (int i = 1; i < n; ++i) {
      const double t = t0_ + (i - 0.5) * dt_;
      const double v = t < 0 ? 0.0 : speed(t);
      const double w = t < 0 ? 0.0 : yaw_rate(t);
      yaw_[i] = yaw_[i - 1] + w * dt_;
      const double mid = 0.5 * (yaw_[i] + yaw_[i - 1]);
      pos_[i] = pos_[i - 1] + v * dt_ * body::Vec3(std::sin(mid), 0.0, std::cos(mid));
    }
  }
  body::Vec3 position(double t) const { return lerp(pos_, t); }
  double yaw(double t) const { return lerp(yaw_, t); }

 private:
  template <class T>
  T lerp(const std::vector<T>& v, double t) const {
    double s = std::clamp((t - t0_) / dt_, 0.0, static_cast<double>(v.size() - 1));
    int i = std::min(static_cast<int>(s), static_cast<int>(v.size()) - 2);
    double w = s - i;
    return (1.0 - w) * v[i] + w * v[i + 1];
  }
  double t0_, dt_;
  std::vector<body::Vec3> pos_;
  std::vector<double> yaw_;
};

struct Context {
  const body::Body& body;
  PoseSolver solver;
  ProceduralParams p;
  Rng rng;
  int frames;
  double duration;
  double scale;     // leg length relative to the average body
  double arm_rest;  // hanging arm abduction that clears the torso
  double stand;     // standing pelvis height

  Context(const body::Body& b, const ProceduralParams& params)
      : body(b), solver(b), p(params), rng(params.seed), frames(params.frames) {
    duration = frames / kFramesPerSecond;
    scale = solver.leg_length() / 0.805;
    // Heavier and more muscular bodies need the arms further out.
    arm_rest = 0.14 + 0.26 * b.shape.weight + 0.10 * b.shape.muscle + rng.uniform(0.0, 0.05);
    stand = solver.standing_pelvis_height(0.997, 0.0);
  }
  double time(int frame) const { return frame / kFramesPerSecond; }
  // Ball of the foot relative to the pelvis in the heading frame.
  body::Vec3 foot_offset(int side, double width) const {
    body::Vec3 o = solver.ball_offset(side);
    return body::Vec3(o.x() * width, 0.0, o.z());
  }
  // Standing targets: upright, arms hanging.
  PoseTargets base() const {
    PoseTargets t;
    t.pelvis = body::Vec3(0.0, stand, 0.0);
    for (auto& a : t.arms) {
      a.abduction = arm_rest;
      a.elbow = 0.25;
    }
    return t;
  }
  // Quiet standing: slow sway and breathing, zero velocity at t = 0.
  void idle(PoseTargets& t, double time) const {
    const double sway = 0.5 * (1.0 - std::cos(2 * kPi * time / 4.0));
    const double breath = 0.5 * (1.0 - std::cos(2 * kPi * time / 3.5));
    t.pelvis.x() += 0.012 * sway * (p.seed % 2 ? 1.0 : -1.0);
    t.spine_flex += 0.015 * breath;
    t.spine_bend += 0.01 * sway;
  }
};

// Feet planted side by side for the whole motion.
std::array<std::vector<Stance>, 2> planted(const Context& c, const body::Vec3& at, double yaw, double width,
                                           double toe_out) {
  std::array<std::vector<Stance>, 2> plan;
  for (int s = 0; s < 2; ++s) {
    Stance st;
    st.start = -1.0;
    st.end = c.duration + 1.0;
    st.ball = at + body::rot_y(yaw) * c.foot_offset(s, width);
    st.ball.y() = at.y();
    st.yaw = yaw + (s == 0 ? toe_out : -toe_out);
    plan[s].push_back(st);
  }
  return plan;
}

// Cyclic stepping along a path: walk, run, turn and spin.
struct Gait {
  double period = 1.0, duty = 0.62;
  double width = 0.6, toe_out = 0.06;
  double bob = 0.02, bob_low = 0.06;  // pelvis drop and the phase of its lowest point
  double sway = 0.02, pelvis_turn = 0.07, lean = 0.03;
  double arm_swing = 0.3, elbow = 0.25, elbow_swing = 0.2, arm_out = 0.0;
  SwingStyle style;
  std::function<double(double)> speed = [](double) { return 0.0; };
  std::function<double(double)> yaw_rate = [](double) { return 0.0; };
  std::function<double(double)> activity = [](double) { return 1.0; };  // 0..1 scales the periodic motion
  double head_lead = 0.0;  // head turns ahead by this many seconds of yaw rate
  double phase = 0.0;      // cycle offset (share of a period) of the feet and the periodic motion
};

// The start-up delay a gait with this cycle offset needs so that it starts
// at rest: at least `base`, and late enough that a foot caught mid-swing at
// t = 0 lands where it took off (before the path moves). Plain (seeded)
// motions keep `base`, as they always had.
double gait_delay(const Context& c, double period, double duty, double phase, double base) {
  double delay = base;
  if (!c.p.explicit_params) return delay;
  for (double offset : {phase, 0.5 + phase}) {
    const double k0 = std::ceil(-offset);  // first stance starting at t >= 0
    const double start = (k0 + offset) * period, prev_end = (k0 - 1 + offset + duty) * period;
    if (start > 0.0 && prev_end < 0.0) delay = std::max(delay, start + 0.5 * duty * period);
  }
  return delay;
}

double radians(double degrees) { return degrees * kPi / 180.0; }

// A swinging foot moves along the chord between its stances; on a curved
// path the chord cuts inwards by stride^2 * curvature / 8 and, for long
// strides, into the other leg. Pinned (explicit) motions keep that under
// 2.5 cm; plain ones keep the curvature they always drew.
double path_curvature(const Context& c, double drawn, double stride) {
  if (!c.p.explicit_params) return drawn;
  const double limit = 8.0 * 0.025 / (stride * stride);
  return std::clamp(drawn, -limit, limit);
}

// A kind's discrete choice: the pinned variant, or one drawn from the seed.
int choose(Context& c, int n) { return c.p.variant >= 0 ? c.p.variant % n : c.rng.pick(n); }

std::vector<PoseTargets> gait_pass(const Context& c, const Gait& g, const Path& path,
                                   const std::array<std::vector<Stance>, 2>& plan, double bob);

std::vector<PoseTargets> run_gait(Context& c, const Gait& g) {
  const Path path(g.speed, g.yaw_rate, c.duration);
  auto pos = [&](double t) { return path.position(t); };
  auto yaw = [&](double t) { return path.yaw(t); };
  std::array<std::vector<Stance>, 2> plan;
  for (int s = 0; s < 2; ++s)
    plan[s] = plan_steps(pos, yaw, g.period, g.duty, (s == 0 ? 0.0 : 0.5) + g.phase, c.duration,
                         c.foot_offset(s, g.width), s == 0 ? g.toe_out : -g.toe_out);
  // The pelvis bob must cover the drop the stride geometry needs at
  // double support; a first pass measures it.
  double bob = g.bob;
  for (int pass = 0; pass < 2; ++pass) {
    std::vector<PoseTargets> out = gait_pass(c, g, path, plan, bob);
    if (pass == 1) return out;
    double need = 0.0;
    for (const PoseTargets& x : out) need = std::max(need, c.solver.pelvis_drop_needed(x, kReach));
    bob += need;
  }
  return {};
}

std::vector<PoseTargets> gait_pass(const Context& c, const Gait& g, const Path& path,
                                   const std::array<std::vector<Stance>, 2>& plan, double bob) {
  std::vector<PoseTargets> out;
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    const double a = g.activity(t);
    const double phase = 2 * kPi * t / g.period + 2 * kPi * g.phase;
    PoseTargets x = c.base();
    const double heading = path.yaw(t);
    const double side = g.sway * a * std::sin(phase - 2 * kPi * (g.duty / 2 - 0.25));
    x.pelvis = path.position(t) + body::rot_y(heading) * body::Vec3(side, 0.0, 0.0);
    x.pelvis.y() = c.stand - bob * a * (0.5 + 0.5 * std::cos(2 * phase - 4 * kPi * g.bob_low));
    x.yaw = heading - g.pelvis_turn * a * std::cos(phase);
    x.pitch = g.lean * a;
    x.spine_twist = 1.6 * g.pelvis_turn * a * std::cos(phase);
    x.spine_flex = 0.3 * g.lean * a;
    x.head_pitch = -0.5 * g.lean * a;
    x.head_yaw = std::clamp(g.head_lead * g.yaw_rate(t), -0.6, 0.6);
    for (int s = 0; s < 2; ++s) {
      const double swing = (s == 0 ? -1.0 : 1.0) * g.arm_swing * a * std::cos(phase);
      ArmAngles& arm = x.arms[s];
      arm.abduction = c.arm_rest + g.arm_out * a;
      arm.flexion = swing;
      arm.elbow = g.elbow + g.elbow_swing * a * 0.5 * (1.0 + std::cos(phase) * (s == 0 ? -1.0 : 1.0));
      x.feet[s] = foot_at(plan[s], t, g.style);
    }
    out.push_back(x);
  }
  return out;
}

// Start-up ramp: still for `delay` seconds, then 0 -> 1 over `ramp_time`
// (the delay lets the first step begin after frame 0, so motions start at
// rest).
std::function<double(double)> ramp(double ramp_time, double delay = 0.35) {
  return [ramp_time, delay](double t) { return body::smootherstep((t - delay) / ramp_time); };
}

std::vector<PoseTargets> walk(Context& c) {
  Gait g;
  const double sp = c.p.speed, amp = c.p.amplitude;
  const double v = 1.0 * sp * c.scale;
  g.period = 0.9 / std::sqrt(sp) * c.p.step_length;
  const double curvature = path_curvature(c, c.rng.uniform(-0.2, 0.2), v * g.period);
  g.duty = 0.58;
  g.phase = c.p.phase;
  auto env = ramp(1.2, gait_delay(c, g.period, g.duty, g.phase, 0.35));
  g.speed = [=](double t) { return v * env(t); };
  g.yaw_rate = [=](double t) { return curvature * v * env(t); };
  g.activity = env;
  g.bob = 0.01 * amp;
  g.arm_swing = 0.28 * amp * std::sqrt(sp);
  g.style.clearance = 0.05;
  g.style.heel_off = 0.35;
  g.style.full_step = 0.4 * c.scale;
  return run_gait(c, g);
}

std::vector<PoseTargets> run(Context& c) {
  Gait g;
  const double sp = c.p.speed, amp = c.p.amplitude;
  const double v = 2.5 * sp * c.scale;
  g.period = 0.72 / std::pow(sp, 0.3) * c.p.step_length;
  // Pinned fast runs gain cadence, not stride, past a 2.3 m stride (a
  // longer one scissors the thighs into each other at the crotch).
  if (c.p.explicit_params) g.period = std::min(g.period, 2.3 * c.scale / v);
  const double curvature = path_curvature(c, c.rng.uniform(-0.1, 0.1), v * g.period);
  g.duty = 0.36;
  g.phase = c.p.phase;
  auto env = ramp(1.5, gait_delay(c, g.period, g.duty, g.phase, 0.35));
  g.width = 0.5;
  g.speed = [=](double t) { return v * env(t); };
  g.yaw_rate = [=](double t) { return curvature * v * env(t); };
  g.activity = env;
  g.bob = 0.05 * amp;
  g.bob_low = 0.18;  // lowest at mid-stance, highest in flight
  g.sway = 0.01;
  g.pelvis_turn = 0.1;
  g.lean = 0.12;
  g.arm_swing = 0.55 * amp;
  g.elbow = 1.5;
  g.elbow_swing = 0.3;
  g.arm_out = 0.05;
  g.style.clearance = 0.16 * amp;
  g.style.heel_off = 0.55;
  g.style.full_step = 0.5 * c.scale;
  // Bend the elbows only as the run picks up.
  std::vector<PoseTargets> out = run_gait(c, g);
  for (int f = 0; f < c.frames; ++f)
    for (auto& a : out[f].arms) a.elbow = 0.25 + (a.elbow - 0.25) * env(c.time(f));
  return out;
}

// In-place turning: a sum of smooth turns (angle, start, duration).
struct Turns {
  std::vector<std::array<double, 3>> turns;
  double rate(double t) const {
    double r = 0.0;
    for (const auto& [angle, start, length] : turns) {
      const double u = (t - start) / length;
      if (u > 0 && u < 1) r += angle / length * 30.0 * u * u * (1 - u) * (1 - u);
    }
    return r;
  }
};

std::vector<PoseTargets> turn(Context& c) {
  const double sp = c.p.speed;
  Turns turns;
  const double length = 1.8 / sp, pause = 0.8 / sp;
  Gait g;
  g.period = 0.9 / sp;
  g.duty = 0.65;
  g.phase = c.p.phase;
  double dir = c.p.direction != 0 ? c.p.direction : c.rng.sign();
  for (double start = gait_delay(c, g.period, g.duty, g.phase, 0.5); start < c.duration; start += length + pause) {
    const double angle = c.p.turn_angle > 0 ? radians(c.p.turn_angle) : c.rng.uniform(0.5 * kPi, kPi) * c.p.amplitude;
    turns.turns.push_back({dir * angle, start, length});
    if (c.rng.uniform(0, 1) < 0.5) dir = -dir;
  }
  const double peak = kPi / length * 1.875;  // largest yaw rate of a 180-degree turn
  g.width = 0.75;
  g.yaw_rate = [turns](double t) { return turns.rate(t); };
  g.activity = [turns, peak](double t) { return std::min(1.0, std::abs(turns.rate(t)) / peak); };
  g.bob = 0.01;
  g.sway = 0.015;
  g.pelvis_turn = 0.0;
  g.arm_swing = 0.08;
  g.head_lead = 0.25;
  g.style.clearance = 0.05;
  g.style.heel_off = 0.15;
  g.style.full_step = 0.15 * c.scale;
  return run_gait(c, g);
}

std::vector<PoseTargets> spin(Context& c) {
  const double sp = c.p.speed;
  const double dir = c.p.direction != 0 ? c.p.direction : c.rng.sign();
  const double omega = dir * (c.p.turn_angle > 0 ? radians(c.p.turn_angle) : 2.6 * sp * c.p.amplitude);
  Gait g;
  g.period = 0.75 / sp;
  // A pinned rate: each foot turns by at most ~115 degrees a step.
  if (c.p.turn_angle > 0) g.period = std::min(g.period, 2.0 / std::abs(omega));
  g.duty = 0.6;
  g.phase = c.p.phase;
  auto env = ramp(1.2, gait_delay(c, g.period, g.duty, g.phase, 0.35));
  g.width = 0.75;
  g.yaw_rate = [=](double t) { return omega * env(t); };
  g.activity = env;
  g.bob = 0.01;
  g.sway = 0.01;
  g.pelvis_turn = 0.0;
  g.arm_swing = 0.1;
  g.arm_out = 0.25;
  g.head_lead = 0.12;
  g.style.clearance = 0.05;
  g.style.heel_off = 0.15;
  g.style.full_step = 0.15 * c.scale;
  return run_gait(c, g);
}

// Repeated two-footed take-offs: a crouch before each, a flight, a landing
// dip; jump and hop differ in size and timing.
struct Leaps {
  double crouch, height, flight;  // m, m, s
  double every;                   // s between take-offs
  double prep, prep_length;       // the crouch starts prep s before take-off and lasts prep_length s
  double land;                    // s of the landing dip
  double arm_dip, arm_swing;      // arms back in the crouch, forward at take-off (rad)
  double forward;                 // m travelled per leap
  double first;                   // s of the first take-off
};

std::vector<PoseTargets> leaps(Context& c, const Leaps& j) {
  std::vector<double> takeoffs;
  for (double t0 = j.first; t0 + j.flight + 0.5 < c.duration; t0 += j.every) takeoffs.push_back(t0);

  std::array<std::vector<Stance>, 2> plan;
  for (int s = 0; s < 2; ++s) {
    double start = -1.0;
    for (std::size_t k = 0; k <= takeoffs.size(); ++k) {
      Stance st;
      st.start = start;
      st.end = k < takeoffs.size() ? takeoffs[k] : c.duration + 1.0;
      st.ball = body::Vec3(0, 0, j.forward * static_cast<double>(k)) + c.foot_offset(s, 0.7);
      st.ball.y() = 0.0;
      st.yaw = s == 0 ? 0.08 : -0.08;
      st.min_lift = k > 0 ? 1.0 : 0.0;
      plan[s].push_back(st);
      if (k < takeoffs.size()) start = takeoffs[k] + j.flight;
    }
  }
  SwingStyle style;
  style.clearance = 0.5 * j.height;  // the legs tuck a little below the rising pelvis
  style.heel_off = 0.5;
  style.heel_share = 0.3;

  std::vector<PoseTargets> out;
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    PoseTargets x = c.base();
    double dip = 0.0, air = 0.0, arms = 0.0, z = 0.0;
    for (std::size_t k = 0; k < takeoffs.size(); ++k) {
      const double t0 = takeoffs[k];
      const double before = bump((t - (t0 - j.prep)) / j.prep_length),
                   after = bump((t - (t0 + j.flight - 0.05)) / j.land);
      dip += before + 0.8 * after;
      air += bump((t - t0) / j.flight);
      arms += -j.arm_dip * before + j.arm_swing * bump((t - (t0 - 0.1)) / (j.flight + 0.3));
      z += j.forward * body::smootherstep((t - t0) / j.flight);
    }
    x.pelvis.y() = c.stand - j.crouch * dip + j.height * air;
    x.pelvis.z() = z;
    x.pitch = 0.25 * dip;
    x.spine_flex = 0.3 * dip;
    x.head_pitch = -0.3 * dip;
    for (int s = 0; s < 2; ++s) {
      x.arms[s].flexion = arms;
      x.arms[s].elbow = 0.3 + 0.2 * dip;
      x.feet[s] = foot_at(plan[s], t, style);
    }
    out.push_back(x);
  }
  return out;
}

// The first take-off: `base` seconds, later by the phase's share of what
// the clip leaves for it (so a phase never pushes the last leap out).
double first_leap(const Context& c, const Leaps& j, double base) {
  const double room = std::clamp(c.duration - base - j.flight - 0.55, 0.0, j.every);
  return base + c.p.phase * room;
}

std::vector<PoseTargets> jump(Context& c) {
  const double sp = c.p.speed, amp = c.p.amplitude;
  Leaps j;
  j.crouch = (0.10 + 0.06 * amp) * c.scale;
  j.height = (0.10 + 0.12 * amp) * c.scale;
  j.flight = 0.3 + 0.12 * amp;
  if (c.p.variant >= 0)
    j.forward = choose(c, 2) == 0 ? 0.0 : 0.3 * c.p.step_length * c.scale;  // in_place, forward
  else
    j.forward = c.rng.uniform(0, 1) < 0.5 ? 0.0 : c.rng.uniform(0.15, 0.45) * c.scale;
  j.every = 2.2 / sp;
  j.prep = 0.55;
  j.prep_length = 0.6;
  j.land = 0.55;
  j.arm_dip = 0.6;
  j.arm_swing = 1.6 * amp;
  j.first = first_leap(c, j, 0.85);
  return leaps(c, j);
}

// Quick small jumps on both feet, one after the other.
std::vector<PoseTargets> hop(Context& c) {
  const double sp = c.p.speed, amp = c.p.amplitude;
  Leaps j;
  j.crouch = (0.03 + 0.03 * amp) * c.scale;
  j.height = (0.04 + 0.05 * amp) * c.scale;
  j.flight = 0.18 + 0.06 * amp;
  j.forward = choose(c, 2) == 0 ? 0.0 : 0.12 * c.p.step_length * c.scale;  // in_place, forward
  j.every = std::max(0.6 / sp, j.flight + 0.22);                           // at least ~7 frames on the ground
  j.prep = 0.2;
  j.prep_length = 0.25;
  j.land = 0.25;
  j.arm_dip = 0.2;
  j.arm_swing = 0.5 * amp;
  j.first = first_leap(c, j, 0.6);
  return leaps(c, j);
}

std::vector<PoseTargets> step_down(Context& c) {
  const double sp = c.p.speed;
  const double ledge = (0.12 + 0.13 * c.rng.uniform(0, 1) * c.p.amplitude) * c.scale;
  const double drawn_reach = c.rng.uniform(0.3, 0.45) * c.scale;
  const double reach = c.p.explicit_params ? 0.375 * c.p.step_length * c.scale : drawn_reach;
  const int lead = choose(c, 2);  // left, right
  const double t_lead = 0.8 + 0.6 * c.p.phase, swing = 0.6 / sp;
  const double t_trail = t_lead + swing + 0.3 / sp;
  std::array<std::vector<Stance>, 2> plan;
  for (int s = 0; s < 2; ++s) {
    const double leave = s == lead ? t_lead : t_trail;
    Stance up, down;
    up.start = -1.0;
    up.end = leave;
    up.ball = c.foot_offset(s, 0.7);
    up.ball.y() = ledge;
    down.start = leave + swing;
    down.end = c.duration + 1.0;
    down.ball = c.foot_offset(s, 0.7) + body::Vec3(0, 0, reach);
    down.ball.y() = 0.0;
    up.yaw = down.yaw = s == 0 ? 0.06 : -0.06;
    down.min_lift = 0.6;
    plan[s] = {up, down};
  }
  SwingStyle style;
  style.clearance = 0.06;
  style.heel_off = 0.25;
  std::vector<PoseTargets> out;
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    PoseTargets x = c.base();
    const double move = body::smootherstep((t - t_lead) / (t_trail + swing - t_lead));
    x.pelvis.y() = c.stand + ledge * (1.0 - move);
    x.pelvis.z() = reach * move;
    // Lean into the step and hold the arms out a little for balance.
    const double effort = bump((t - t_lead) / (t_trail + swing - t_lead));
    x.pitch = 0.1 * effort;
    x.head_pitch = 0.15 * effort;
    c.idle(x, std::max(0.0, t - (t_trail + swing)));
    for (int s = 0; s < 2; ++s) {
      x.arms[s].abduction += 0.25 * effort;
      x.arms[s].flexion = (s == lead ? -0.2 : 0.25) * effort;
      x.feet[s] = foot_at(plan[s], t, style);
    }
    out.push_back(x);
  }
  return out;
}

std::vector<PoseTargets> arm_raise(Context& c) {
  const double sp = c.p.speed, amp = c.p.amplitude;
  bool front = false;
  int which = 0;  // both, left, right, alternating
  if (c.p.variant >= 0) {
    front = c.p.variant % 8 < 4;
    which = c.p.variant % 4;
  } else {
    front = c.rng.uniform(0, 1) < 0.5;
    which = c.rng.pick(4);
  }
  const double period = 2.6 / sp;
  const double delay = c.p.phase * std::min(period, c.duration / 3);
  const double top = std::min(2.8, 2.3 * amp + 0.3);
  auto plan = planted(c, body::Vec3::Zero(), 0.0, 0.7, 0.06);
  std::vector<PoseTargets> out;
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    PoseTargets x = c.base();
    c.idle(x, t);
    const double u = (t - delay) / period;  // cycles since the first raise began
    for (int s = 0; s < 2; ++s) {
      const bool moves = which == 0 || which == 3 || which == s + 1;
      const double shift = which == 3 && s == 1 ? 0.5 : 0.0;
      const double r = moves ? plateau(u - shift, 0.35, 0.1) * (u >= shift ? 1.0 : 0.0) : 0.0;
      ArmAngles& a = x.arms[s];
      if (front) {
        a.flexion = top * r;
        a.abduction = c.arm_rest * (1.0 - 0.5 * r);
      } else {
        a.abduction = c.arm_rest + (top - c.arm_rest) * r;
        a.twist = 0.6 * r;  // palms turn up as the arm rises
      }
      a.elbow = 0.25 - 0.1 * r;
      a.clavicle = 0.3 * r * r;
      x.feet[s] = foot_at(plan[s], t, SwingStyle());
    }
    out.push_back(x);
  }
  return out;
}

std::vector<PoseTargets> wave(Context& c) {
  const double sp = c.p.speed, amp = c.p.amplitude;
  const int side = choose(c, 2);  // left, right
  const double freq = 1.8 * sp;
  const double t_up = 0.4 + 0.6 * c.p.phase, rise = 0.9;
  auto plan = planted(c, body::Vec3::Zero(), 0.0, 0.7, 0.06);
  std::vector<PoseTargets> out;
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    PoseTargets x = c.base();
    c.idle(x, t);
    const double up = body::smootherstep((t - t_up) / rise);
    const double waving = body::smootherstep((t - t_up - 0.6 * rise) / 0.6);
    ArmAngles& a = x.arms[side];
    a.abduction = c.arm_rest + (1.85 - c.arm_rest) * up;
    a.flexion = 0.25 * up;
    a.twist = 1.45 * up;
    a.elbow = 0.25 + 1.0 * up + 0.4 * amp * waving * std::sin(2 * kPi * freq * (t - t_up - 0.6 * rise));
    a.clavicle = 0.15 * up;
    x.spine_bend = (side == 0 ? -0.05 : 0.05) * up;
    for (int s = 0; s < 2; ++s) x.feet[s] = foot_at(plan[s], t, SwingStyle());
    out.push_back(x);
  }
  return out;
}

std::vector<PoseTargets> squat(Context& c) {
  const double sp = c.p.speed, amp = c.p.amplitude;
  const double depth = std::min(0.42, (0.22 + 0.12 * amp)) * c.scale;
  const double period = 3.0 / sp;
  const double delay = c.p.phase * std::min(period, c.duration / 3);
  auto plan = planted(c, body::Vec3::Zero(), 0.0, 1.0, 0.3);
  std::vector<PoseTargets> out;
  for (int f = 0; f < c.frames; ++f) {
    const double t = c.time(f);
    PoseTargets x = c.base();
    const double u = (t - delay) / period;
    const double r = u < 0.0 ? 0.0 : plateau(u, 0.35, 0.08);
    x.pelvis.y() = c.stand - depth * r;
    x.pelvis.z() = -0.35 * depth * r;
    x.pitch = 0.45 * r;
    x.spine_flex = 0.2 * r;
    x.head_pitch = -0.45 * r;
    for (int s = 0; s < 2; ++s) {
      x.arms[s].flexion = 1.3 * r;
      x.arms[s].abduction = c.arm_rest * (1.0 - 0.4 * r);
      x.arms[s].elbow = 0.25;
      x.feet[s] = foot_at(plan[s], t, SwingStyle());
    }
    out.push_back(x);
  }
  return out;
}

using Generator = std::vector<PoseTargets> (*)(Context&);
const std::vector<std::pair<std::string, Generator>>& generators() {
  static const std::vector<std::pair<std::string, Generator>> g = {
      {"walk", walk}, {"run", run},    {"turn", turn},           {"spin", spin},
      {"jump", jump}, {"hop", hop},    {"step_down", step_down}, {"arm_raise", arm_raise},
      {"wave", wave}, {"squat", squat}};
  return g;
}

// Lowers the pelvis where a leg cannot reach its foot: the needed drop is
// spread with a max filter and a Gaussian so the correction stays smooth
// and still covers every frame.
void keep_feet_reachable(const Context& c, std::vector<PoseTargets>& targets) {
  std::vector<double> need(targets.size());
  for (std::size_t i = 0; i < targets.size(); ++i) need[i] = c.solver.pelvis_drop_needed(targets[i], kReach);
  const std::vector<double> drop = upper_envelope(need, kGuardSigma);
  for (std::size_t i = 0; i < targets.size(); ++i) targets[i].pelvis.y() -= drop[i];
}

}  // namespace

const std::vector<std::string>& procedural_kinds() {
  static const std::vector<std::string> kinds = [] {
    std::vector<std::string> k;
    for (const auto& [name, gen] : generators()) k.push_back(name);
    return k;
  }();
  return kinds;
}

std::unique_ptr<PoseTrack> make_procedural(const ProceduralParams& params, const body::Body& body) {
  Generator gen = nullptr;
  for (const auto& [name, g] : generators())
    if (name == params.kind) gen = g;
  if (!gen) {
    std::string list;
    for (const std::string& k : procedural_kinds()) list += (list.empty() ? "" : ", ") + k;
    throw InputError("motion", "procedural:" + params.kind, "one of procedural:{" + list + "}",
                     "'" + params.kind + "'");
  }
  if (params.frames < 1) throw InputError("motion", "frames", "at least 1", std::to_string(params.frames));
  if (!(params.speed > 0.2 && params.speed < 3.0) || !(params.amplitude > 0.0 && params.amplitude < 3.0))
    throw InputError("motion", "procedural:" + params.kind, "speed in (0.2, 3) and amplitude in (0, 3)",
                     std::to_string(params.speed) + ", " + std::to_string(params.amplitude));
  if (!(params.phase >= 0.0 && params.phase <= 1.0) || !(params.step_length >= 0.2 && params.step_length <= 3.0) ||
      !(params.turn_angle >= 0.0 && params.turn_angle <= 720.0) || std::abs(params.direction) > 1)
    throw InputError("motion", "procedural:" + params.kind,
                     "phase in [0, 1], step in [0.2, 3], turn in [0, 720] degrees, dir left or right",
                     describe_procedural(params));
  Context c(body, params);
  std::vector<PoseTargets> targets = gen(c);
  keep_feet_reachable(c, targets);
  std::vector<body::Pose> poses;
  poses.reserve(targets.size());
  for (const PoseTargets& t : targets) {
    body::Pose p = c.solver.solve(t);
    if (!poses.empty())
      for (std::size_t j = 0; j < p.local.size(); ++j)
        p.local[j] = body::same_hemisphere(p.local[j], poses.back().local[j]);
    poses.push_back(std::move(p));
  }
  return std::make_unique<PoseTrack>(std::move(poses), describe_procedural(params));
}

}  // namespace layers::motion
