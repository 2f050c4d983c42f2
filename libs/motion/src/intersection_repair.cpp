// Room for the cloth under the arms and between the thighs, and smooth repair of
// self-intersecting frames (see intersection_repair.h).
#include "intersection_repair.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "layers/body/skinning.h"
#include "smoothing.h"

namespace layers::motion {
namespace {

constexpr double kStep = 0.05;        // rad per search step
constexpr double kSpreadSigma = 2.0;  // frames: corrections spread over about 3 sigma each side
constexpr int kRounds = 6;            // search / spread rounds
constexpr int kRunGap = 12;           // frames: affected frames closer than this share one way
constexpr double kRoomSlack = 0.002;  // m: what a room turn may take from a gap before it counts as harm

// Limb roots (left arm, right arm, left leg, right leg) and the joint whose
// axes the corrections turn about (chest for arms, pelvis for legs).
struct Limbs {
  std::array<int, 4> root, frame;
  explicit Limbs(const body::Skeleton& sk)
      : root{sk.require("LeftArm"), sk.require("RightArm"), sk.require("LeftUpLeg"), sk.require("RightUpLeg")},
        frame{sk.require("Spine1"), sk.require("Spine1"), 0, 0} {}
};

// Correction channels: which limb turns, about which axis of its frame
// (z forward: abduction; x lateral: swing), in which direction.
struct Channel {
  int limb;
  int axis;
  double sign;
};
constexpr int kChannels = 8;
constexpr Channel kChannel[kChannels] = {
    {0, 2, +1.0}, {1, 2, -1.0}, {2, 2, +1.0}, {3, 2, -1.0},  // abduct each limb outward
    {0, 0, -1.0}, {1, 0, -1.0},                              // swing an arm forward
    {0, 0, +1.0}, {1, 0, +1.0},                              // swing an arm backward
};
using Corrections = std::array<double, kChannels>;
constexpr int kWays = 3;
// Channel of arm a (0 left, 1 right) for each way: abduct, forward, backward.
constexpr int kArmChannel[kWays][2] = {{0, 1}, {4, 5}, {6, 7}};
// Channel of leg l (0 left, 1 right): abduct.
constexpr int kLegChannel[2] = {2, 3};

body::Pose corrected(const body::Skeleton& sk, const Limbs& limbs, const body::Pose& pose, const Corrections& c) {
  if (std::all_of(c.begin(), c.end(), [](double x) { return x == 0.0; })) return pose;
  const body::JointTransforms t = body::forward_kinematics(sk, pose);
  body::Pose out = pose;
  for (int ch = 0; ch < kChannels; ++ch) {
    if (c[ch] == 0.0) continue;
    const Channel& k = kChannel[ch];
    const int j = limbs.root[k.limb];
    const body::Quat parent = t.rotation[sk.parents[j]];
    const body::Vec3 axis = t.rotation[limbs.frame[k.limb]] * body::Vec3::Unit(k.axis);
    out.local[j] = (parent.conjugate() * body::axis_angle(axis, k.sign * c[ch]) * parent * out.local[j]).normalized();
  }
  return out;
}

class Repair {
 public:
  Repair(const body::Body& body, const body::SelfIntersection& si, const RepairLimits& limits,
         const std::vector<body::Pose>& original)
      : body_(body), si_(si), limits_(limits), limbs_(body.skeleton), original_(original) {}

  body::FrameIntersection check(int f, const Corrections& c) const {
    geometry::Points v;
    const body::Pose p = corrected(body_.skeleton, limbs_, original_[f], c);
    body::skin(body_.rest.vertices, body_.weights, body_.skeleton, body::forward_kinematics(body_.skeleton, p), v);
    return si_.check(v, limits_.crossings);
  }
  // A full check seen as check() gives it: the crossings of limbs not
  // aimed at left out.
  body::FrameIntersection masked(body::FrameIntersection r) const {
    r.crossings = 0;
    for (int limb = 0; limb < 4; ++limb) {
      if (!limits_.crossings[limb]) r.limb_crossings[limb] = 0;
      r.crossings += r.limb_crossings[limb];
    }
    return r;
  }
  body::Pose pose(int f, const Corrections& c) const { return corrected(body_.skeleton, limbs_, original_[f], c); }

  // Steps the channels of the offending limbs (arms the way given per
  // arm) until frame f is clean or at the limits. A limb is offending while
  // deeper than the tolerance (or short of the gap) or, until its limit is reached, while it
  // crosses another region exactly; at its limit with crossings left its
  // turn goes back to where it started and only its depth counts. Returns
  // 2 when every exact crossing cleared, 1 when only the depth verdict
  // did, 0 when not even that.
  int search(int f, Corrections& c, body::FrameIntersection r, const std::array<int, 2>& way) const {
    const Corrections start = c;
    std::array<bool, 4> exact{true, true, true, true};
    // One probe with every crossing limb at its limit: a limb still
    // crossing there gives its crossings up at once (the steps would not
    // clear them, and cost a check each).
    Corrections probe = c;
    bool crossing = false;
    for (int limb = 0; limb < 4; ++limb) {
      if (r.limb_crossings[limb] == 0) continue;
      crossing = true;
      probe[channel(limb, way)] = limit(limb);
    }
    if (crossing) {
      const body::FrameIntersection p = check(f, probe);
      for (int limb = 0; limb < 4; ++limb) exact[limb] = p.limb_crossings[limb] == 0;
    }
    for (;;) {
      bool offending = false, moved = false;
      for (int limb = 0; limb < 4; ++limb) {
        const bool deep = r.limb_shortfall[limb] > 0.0;  // deeper than the tolerance or short of the gap
        if (!deep && !(exact[limb] && r.limb_crossings[limb] > 0)) continue;
        offending = true;
        const int ch = channel(limb, way);
        if (c[ch] + kStep <= limit(limb) + 1e-9) {
          c[ch] += kStep;
          moved = true;
        } else if (exact[limb]) {
          exact[limb] = false;
          c[ch] = start[ch];
          moved = true;
        }
      }
      if (!offending) return std::all_of(exact.begin(), exact.end(), [](bool e) { return e; }) ? 2 : 1;
      if (!moved) return 0;
      r = check(f, c);
    }
  }

 private:
  static int channel(int limb, const std::array<int, 2>& way) { return limb < 2 ? kArmChannel[way[limb]][limb] : limb; }
  double limit(int limb) const { return limb < 2 ? limits_.arm : limits_.leg; }

  const body::Body& body_;
  const body::SelfIntersection& si_;
  RepairLimits limits_;
  Limbs limbs_;
  const std::vector<body::Pose>& original_;
};

// Runs of affected frames per arm: [first, last] with gaps of at most
// kRunGap unaffected frames inside.
std::vector<std::pair<int, int>> runs(const std::vector<char>& affected) {
  std::vector<std::pair<int, int>> out;
  const int n = static_cast<int>(affected.size());
  for (int f = 0; f < n; ++f) {
    if (!affected[f]) continue;
    if (!out.empty() && f - out.back().second <= kRunGap)
      out.back().second = f;
    else
      out.emplace_back(f, f);
  }
  return out;
}

}  // namespace

RoomReport make_room(const body::Body& body, const body::SelfIntersection& checker, Room where, double room,
                     double limit, std::vector<body::Pose>& poses) {
  RoomReport report;
  const int n = static_cast<int>(poses.size());
  const int steps = static_cast<int>(std::floor(limit / kStep + 1e-9));
  if (room <= 0.0 || steps <= 0 || n == 0) return report;
  const Limbs limbs(body.skeleton);
  const std::array<bool, 4> no_crossings{false, false, false, false};  // the gaps only
  // The abduction channels of the two limbs (kChannel): arms 0 and 1, legs 2 and 3.
  const std::array<int, 2> channel = where == Room::arms ? std::array<int, 2>{kArmChannel[0][0], kArmChannel[0][1]}
                                                         : std::array<int, 2>{kLegChannel[0], kLegChannel[1]};
  // Each arm's gap depends on its own turn only, so both arms turn by the
  // same angle in one check. The thighs share one gap: both legs turn by
  // the same angle, and both "limbs" below see that gap.
  const auto gaps = [&](const body::Pose& p, double turn) {
    Corrections c{};
    for (int a = 0; a < 2; ++a) c[channel[a]] = turn;
    geometry::Points v;
    body::skin(body.rest.vertices, body.weights, body.skeleton,
               body::forward_kinematics(body.skeleton, corrected(body.skeleton, limbs, p, c)), v);
    const body::FrameIntersection r = checker.check(v, no_crossings);
    return where == Room::arms ? r.arm_gap : std::array<double, 2>{r.thigh_gap, r.thigh_gap};
  };
  // Per limb and frame: the turn it needs (the smallest that gives the
  // room, else the one that gives the most when that beats no turn) and
  // the largest turn that is harmless (no smaller turn takes the limb
  // closer than min(its gap, room) - kRoomSlack; in some poses, an arm
  // swung forward and in among them, abduction brings the limb nearer its
  // neighbour). Frames with the room already need nothing; they are scanned
  // for their harmless turn only where a neighbour's turn spreads to them.
  std::array<std::vector<double>, 2> need{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
  std::array<std::vector<double>, 2> ceiling{std::vector<double>(n, limit), std::vector<double>(n, limit)};
  std::vector<char> scanned(n, 0);
  std::vector<std::array<double, 2>> g(static_cast<std::size_t>(steps) + 1);
  // `unturned`: the frame's gaps without a turn.
  const auto scan = [&](int f, const std::array<double, 2>& unturned) {
    scanned[f] = 1;
    g[0] = unturned;
    for (int k = 1; k <= steps; ++k) g[k] = gaps(poses[f], k * kStep);
    for (int a = 0; a < 2; ++a) {
      int reach = -1, best = 0, safe = 0;
      for (int k = 0; k <= steps; ++k) {
        if (reach < 0 && g[k][a] >= room) reach = k;
        if (g[k][a] > g[best][a]) best = k;
      }
      const double floor_gap = std::min(g[0][a], room) - kRoomSlack;
      while (safe < steps && g[safe + 1][a] >= floor_gap) ++safe;
      const int k = reach >= 0 ? reach : (g[best][a] > g[0][a] + kRoomSlack ? best : 0);
      need[a][f] = k * kStep;
      ceiling[a][f] = safe * kStep;
    }
  };
  std::vector<std::array<double, 2>> g0(n);
  for (int f = 0; f < n; ++f) {
    g0[f] = gaps(poses[f], 0.0);
    if (g0[f][0] < room || g0[f][1] < room) scan(f, g0[f]);
  }
  // Smooth over neighbouring frames: an envelope above the needs, one
  // below the harmless turns (the lower one wins where they meet).
  std::array<std::vector<double>, 2> up{upper_envelope(need[0], kSpreadSigma), upper_envelope(need[1], kSpreadSigma)};
  for (int f = 0; f < n; ++f)
    if (!scanned[f] && (up[0][f] >= 1e-6 || up[1][f] >= 1e-6)) scan(f, g0[f]);
  std::array<std::vector<double>, 2> applied;
  for (int a = 0; a < 2; ++a) {
    const std::vector<double> down = lower_envelope(ceiling[a], kSpreadSigma);
    applied[a].resize(n);
    for (int f = 0; f < n; ++f) applied[a][f] = std::clamp(std::min(up[a][f], down[f]), 0.0, limit);
  }
  for (int f = 0; f < n; ++f) {
    Corrections c{};
    for (int a = 0; a < 2; ++a) c[channel[a]] = applied[a][f];
    if (c[channel[0]] < 1e-6 && c[channel[1]] < 1e-6) continue;
    ++report.frames;
    report.turn = std::max({report.turn, c[channel[0]], c[channel[1]]});
    poses[f] = corrected(body.skeleton, limbs, poses[f], c);
  }
  return report;
}

void repair_intersections(const body::Body& body, const body::SelfIntersection& checker, const RepairLimits& limits,
                          std::vector<body::Pose>& poses, std::vector<body::FrameIntersection>& found) {
  const int n = static_cast<int>(poses.size());
  const std::vector<body::Pose> original = poses;
  const Repair repair(body, checker, limits, original);
  // Work on the crossings aimed at (the caller re-checks for the full count).
  for (body::FrameIntersection& r : found) r = repair.masked(r);

  // Which way each arm goes (abduct, forward, backward), per frame.
  std::array<std::vector<int>, 2> way{std::vector<int>(n, 0), std::vector<int>(n, 0)};
  // clears[f][w]: what way w alone achieves on frame f (search()'s 0, 1
  // or 2), -1 untried.
  std::vector<std::array<int, kWays>> clears(n, {-1, -1, -1});
  auto try_way = [&](int f, int w) {
    if (clears[f][w] < 0) {
      Corrections c{};
      clears[f][w] = repair.search(f, c, found[f], {w, w});
    }
    return clears[f][w];
  };
  // Per run of frames where an arm is deep, the way that passes the depth
  // verdict on the most frames, then clears the exact crossings on the
  // most; abduction when it clears every frame of the run. Frames that
  // only cross keep abduction, which turns the arm away from the body.
  for (int a = 0; a < 2; ++a) {
    std::vector<char> deep(n);
    for (int f = 0; f < n; ++f) deep[f] = found[f].limb_shortfall[a] > 0.0;
    for (const auto& [first, last] : runs(deep)) {
      const long frames = std::count(deep.begin() + first, deep.begin() + last + 1, 1);
      std::array<long, kWays> score{};
      const auto score_of = [&](int w) {
        for (int f = first; f <= last; ++f) {
          if (!deep[f]) continue;
          const int q = try_way(f, w);
          score[w] += (q >= 1 ? 2 * frames + 1 : 0) + (q == 2 ? 1 : 0);
        }
      };
      score_of(0);
      if (score[0] < frames * (2 * frames + 2))
        for (int w = 1; w < kWays; ++w) score_of(w);
      const int best = static_cast<int>(std::max_element(score.begin(), score.end()) - score.begin());
      for (int f = first; f <= last; ++f) way[a][f] = best;
    }
  }

  std::array<std::vector<double>, kChannels> need, applied;
  for (int ch = 0; ch < kChannels; ++ch) {
    need[ch].assign(n, 0.0);
    applied[ch].assign(n, 0.0);
  }
  auto at = [&](const std::array<std::vector<double>, kChannels>& v, int f) {
    Corrections c;
    for (int ch = 0; ch < kChannels; ++ch) c[ch] = v[ch][f];
    return c;
  };
  for (int round = 0; round < kRounds; ++round) {
    bool grew = false;
    for (int f = 0; f < n; ++f) {
      if (!found[f].needs_repair()) continue;
      Corrections c = at(applied, f);
      repair.search(f, c, found[f], {way[0][f], way[1][f]});
      for (int ch = 0; ch < kChannels; ++ch) {
        grew = grew || c[ch] > need[ch][f] + 1e-12;
        need[ch][f] = std::max(need[ch][f], c[ch]);
      }
    }
    if (!grew) break;
    for (int ch = 0; ch < kChannels; ++ch) applied[ch] = upper_envelope(need[ch], kSpreadSigma);
    for (int f = 0; f < n; ++f) {
      const Corrections c = at(applied, f);
      if (std::all_of(c.begin(), c.end(), [](double x) { return x < 1e-6; })) continue;
      poses[f] = repair.pose(f, c);
      found[f] = repair.check(f, c);
    }
  }
}

}  // namespace layers::motion
