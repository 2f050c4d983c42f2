// The frame loop of the solver (see solver.h): frame set-up (supports,
// refactorisation), then per substep prediction, elastic iterations with
// supports, contact projections and velocities, in a fixed order.
#include "layers/sim/solver.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>
#include <string>
#include <utility>

#include "body_collider.h"
#include "body_pinch.h"
#include "cloth_contact.h"
#include "collision_pass.h"
#include "contact_candidates.h"
#include "fold_limit.h"
#include "layers/core/error.h"
#include "projective.h"
#include "strain_limit.h"

namespace layers::sim {

// Per-cloth solver state and the contact machinery.
struct Solver::Impl {
  detail::BodyCollider body;
  detail::LayerContact layers;
  detail::SelfContact self;
  std::vector<std::unique_ptr<detail::ProjectiveSystem>> elastic;
  std::vector<detail::StrainLimiter> limiters;
  std::vector<detail::FoldLimiter> folds;
  std::vector<detail::BodyCollider::Memory> body_memory;
  std::vector<detail::LayerContact::Memory> layer_memory;
  std::vector<Vec3s> forces;     // wind forces of the substep
  std::vector<Vec3s> rhs;        // extra right-hand side of the current iteration
  std::vector<Vec3s> reactions;  // forces from outer garments' supports, previous iteration
  std::vector<Vec3s> next_reactions;
  std::vector<Vec3s> push;                         // cloth-cloth contact pushes of the substep (no velocity)
  std::vector<int> order;                          // cloths by layer, then index
  std::vector<double> body_push;                   // largest body push per cloth in the substep
  std::vector<std::vector<std::uint8_t>> claimed;  // per cloth: attachment aimed this iteration
  std::vector<std::uint8_t> held;                  // scratch: vertices touching the body or an inner layer
  detail::CollisionPass pass;
  detail::BodyPinch pinch;                               // the body's pinch zones, for the pass
  const std::vector<std::uint8_t>* pinch_now = nullptr;  // this frame's (null: no pass or no body)
  std::vector<Cloth::State*> states;                     // per cloth, for the collision pass
  std::vector<std::vector<std::uint8_t>> reverted;       // per cloth: put back by the collision pass this substep
  std::vector<Vec3s> before_pass, before_cap;            // per cloth: positions before the pass and before its cap
  std::vector<std::vector<std::uint8_t>> moved;          // per cloth: moved by the cap after the pass
  // The shared broad phase (contact_candidates.h): read by the layer and
  // body edge contacts and the collision pass.
  detail::ContactLayout layout;
  detail::ContactCandidates candidates;

  Impl() { pass.share(&layout, &candidates); }

  // Makes the candidates hold every pair for the cloths' positions now and
  // at the start of the substep (and the body's frame sweep).
  void ensure_candidates(const std::vector<Cloth>& cloths, const SolverConfig& c, bool with_body) {
    layout.update(cloths, with_body ? &body.topology().faces : nullptr, with_body ? &body.edges() : nullptr,
                  with_body ? &body.frame_start() : nullptr);
    candidates.set_reach(
        {c.collision_pass ? c.collision_gap : 0.0, c.layer_edge_thickness, c.body_edge_thickness, kContactMargin});
    const auto at = [&](int g, bool start) -> const Vec3& {
      const int ci = layout.owner[g];
      const Cloth::State& s = cloths[ci].state();
      return (start ? s.x_start : s.x)[g - layout.offset[ci]];
    };
    detail::ContactCandidates::BodySweep sweep;
    if (with_body) sweep = {&body.frame_start(), &body.frame_end(), body.sweep_revision()};
    candidates.ensure(
        layout, [&](int g) -> const Vec3& { return at(g, true); }, [&](int g) -> const Vec3& { return at(g, false); },
        sweep);
  }

  // Room each cloth vertex gets around its reference in the candidate list
  // (m): more makes longer lists, less makes them again more often (on
  // bench_sim's 4k walk, before references were put ahead: 1 mm, 35 lists
  // a frame; 3 mm, 5.5; 6 mm, 3 with twice the pairs of 3 mm).
  static constexpr double kContactMargin = 0.003;

  void add(int n) {
    elastic.push_back(std::make_unique<detail::ProjectiveSystem>());
    limiters.emplace_back();
    folds.emplace_back();
    body_memory.emplace_back();
    body_memory.back().resize(n);
    layer_memory.emplace_back();
    layer_memory.back().resize(n);
    for (auto* v : {&forces, &rhs, &reactions, &next_reactions, &push}) v->emplace_back(n, Vec3::Zero());
    claimed.emplace_back(n, 0);
    reverted.emplace_back(n, 0);
    before_pass.emplace_back();
    before_cap.emplace_back();
    moved.emplace_back(n, 0);
  }
};

namespace {

using Clock = std::chrono::steady_clock;

constexpr double kPi = 3.14159265358979323846;
// Sweeps of the fold cap per substep: each fold is corrected again in the
// next substep, so a few suffice.
constexpr int kFoldSweeps = 4;
// Rounds of (strain cap, collision pass again) after the collision pass.
constexpr int kCapAfterPass = 3;

double seconds_since(Clock::time_point& t) {
  const Clock::time_point now = Clock::now();
  const double s = std::chrono::duration<double>(now - t).count();
  t = now;
  return s;
}

}  // namespace

Solver::Solver(SolverConfig config) : config_(std::move(config)), impl_(std::make_unique<Impl>()) { check(config_); }

Solver::~Solver() = default;
Solver::Solver(Solver&&) noexcept = default;
Solver& Solver::operator=(Solver&&) noexcept = default;

void Solver::set_config(const SolverConfig& config) {
  check(config);
  config_ = config;
}

int Solver::add_cloth(Cloth cloth) {
  impl_->add(cloth.num_vertices());
  cloths_.push_back(std::move(cloth));
  impl_->order.resize(cloths_.size());
  std::iota(impl_->order.begin(), impl_->order.end(), 0);
  std::stable_sort(impl_->order.begin(), impl_->order.end(),
                   [&](int a, int b) { return cloths_[a].layer() < cloths_[b].layer(); });
  return num_cloths() - 1;
}

Cloth& Solver::cloth(int index) {
  if (index < 0 || index >= num_cloths()) {
    throw Error("Solver::cloth: index " + std::to_string(index) + " out of range [0, " + std::to_string(num_cloths()) +
                ")");
  }
  return cloths_[index];
}

const Cloth& Solver::cloth(int index) const { return const_cast<Solver*>(this)->cloth(index); }

void Solver::set_body(const geometry::TriMesh& body) {
  impl_->body.reset(body);
  impl_->pinch.forget();
  body_ = body;
  for (std::size_t i = 0; i < cloths_.size(); ++i) impl_->body_memory[i].resize(cloths_[i].num_vertices());
}

void Solver::set_body_positions(const geometry::Points& positions) {
  if (!has_body()) throw InputError("body", "positions", "set_body() before set_body_positions()", "no body");
  impl_->body.set_pose(positions);
  impl_->pinch.forget();
  body_.vertices = positions;
}

bool Solver::has_body() const { return !impl_->body.empty(); }

void Solver::step(const geometry::Points& body_next, const Wind& wind) {
  if (!has_body()) throw InputError("body", "next positions", "set_body() before step(body_next)", "no body");
  advance(&body_next, wind);
}

void Solver::step(const Wind& wind) { advance(nullptr, wind); }

template <class F>
void Solver::for_each_layer_pair(F&& f) {
  // Every (inner, outer) pair of cloths on different layers, inner first;
  // friction is the mean of their self-friction coefficients.
  for (int a : impl_->order) {
    for (int b : impl_->order) {
      if (cloths_[a].layer() >= cloths_[b].layer()) continue;
      f(a, b, 0.5 * (cloths_[a].material().self_friction + cloths_[b].material().self_friction));
    }
  }
}

// advance() reads as its phases, each below with what it reads and
// changes; the timings are taken between them.
void Solver::advance(const geometry::Points* body_next, const Wind& wind) {
  Clock::time_point start = Clock::now(), t = start;
  if (!std::isfinite(wind.strength) || wind.strength < 0 || !wind.direction.allFinite()) {
    throw InputError("wind", "strength", "a finite number >= 0 and a finite direction", std::to_string(wind.strength));
  }
  Impl& m = *impl_;
  const bool body = has_body();
  if (body) m.body.begin_frame(body_next);
  const SolverConfig& c = config_;
  m.pinch_now =
      body && c.collision_pass ? &m.pinch.update(m.body, body_.faces, cloths_, c.validation.pinch_distance) : nullptr;
  const int n = c.substeps;
  const double h = 1.0 / (c.fps * n);
  Wind unit_wind = wind;
  if (wind.direction.norm() > 0) unit_wind.direction.normalize();

  prepare_frame(h, body);
  timings_.elastic += seconds_since(t);
  const long builds = m.candidates.builds(), body_builds = m.candidates.body_builds(),
             refreshes = m.candidates.refreshes();
  for (int k = 0; k < n; ++k) {
    const double step2 = predict(h, unit_wind);
    timings_.predict += seconds_since(t);
    // The body's edge-edge pass on every body_edge_every-th substep.
    const double body_edges = k % c.body_edge_every == 0 ? c.body_edge_thickness : 0.0;
    if (body) {
      m.body.begin_substep(static_cast<double>(k + 1) / n, 2 * std::sqrt(step2) + c.body_thickness, c.body_thickness);
      for (std::size_t ci = 0; ci < cloths_.size(); ++ci) m.body.locate_supports(cloths_[ci].state_, m.body_memory[ci]);
    }
    timings_.body_contact += seconds_since(t);
    elastic_iterations(body);
    cap_folds_and_strain();
    timings_.elastic += seconds_since(t);
    project_layer_contacts();
    timings_.layer_contact += seconds_since(t);
    project_self_contacts();
    timings_.self_contact += seconds_since(t);
    project_body_contacts(body, body_edges, h);
    timings_.body_contact += seconds_since(t);
    settle_outer_layers();
    timings_.layer_contact += seconds_since(t);
    recap_strain(body);
    timings_.strain_cap += seconds_since(t);
    // The continuous-collision safety pass, after every position edit.
    if (c.collision_pass) {
      collision_pass(body);
    } else {
      for (auto& r : m.reverted) std::fill(r.begin(), r.end(), 0);
    }
    timings_.collision_pass += seconds_since(t);
    update_velocities(h);
    timings_.predict += seconds_since(t);
    const detail::ContactCandidates& cc = m.candidates;
    timings_.candidate_pairs +=
        static_cast<long>(cc.cloth_vertex_face().size() + cc.cloth_edge_edge().size() + cc.body_vertex_face().size() +
                          cc.body_face_vertex().size() + cc.body_edge_edge().size());
  }
  timings_.candidate_builds += m.candidates.builds() - builds;
  timings_.candidate_body_builds += m.candidates.body_builds() - body_builds;
  timings_.candidate_refreshes += m.candidates.refreshes() - refreshes;

  if (body) {
    m.body.end_frame();
    if (body_next) body_.vertices = *body_next;
  }
  ++frame_;
  ++timings_.frames;
  timings_.total += std::chrono::duration<double>(Clock::now() - start).count();
}

// Frame set-up: supports of this frame, and the factorisations they need.
void Solver::prepare_frame(double h, bool body) {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
    detail::ProjectiveSystem& system = *m.elastic[ci];
    if (!system.current(cloths_[ci], h)) system.build(cloths_[ci], h);
    const Cloth::State& s = cloths_[ci].state_;
    detail::BodyCollider::Memory& bm = m.body_memory[ci];
    detail::LayerContact::Memory& lm = m.layer_memory[ci];
    if (body) m.body.make_supports(s, bm);
    detail::LayerContact::make_supports(s, lm);
    std::vector<std::uint8_t>& wanted = m.claimed[ci];
    wanted.assign(s.x.size(), 0);
    for (std::size_t i = 0; i < wanted.size(); ++i) wanted[i] = (body && bm.wanted[i]) || lm.wanted[i];
    system.update_attachments(wanted, c.support_stiffness);
  }
}

// Prediction: gravity, wind, air damping; returns the largest squared
// step a vertex takes (the body contact's search reach).
double Solver::predict(double h, const Wind& unit_wind) {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  const Vec3 gravity(c.gravity[0], c.gravity[1], c.gravity[2]);
  const double damping = std::exp(-c.air_damping * h);
  double step2 = 0;
  for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
    Cloth::State& s = cloths_[ci].state_;
    Vec3s& force = m.forces[ci];
    std::fill(force.begin(), force.end(), Vec3::Zero());
    add_wind_forces(cloths_[ci].topology().faces, s.x, unit_wind, c.wind_pressure, force);
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      s.x_start[i] = s.x[i];
      if (s.inv_mass[i] == 0.0) continue;
      Vec3 v = (s.v[i] + h * (gravity + s.inv_mass[i] * force[i])) * damping;
      const double speed = v.norm();
      if (c.max_speed > 0 && speed > c.max_speed) v *= c.max_speed / speed;
      s.v[i] = v;
      s.x[i] += h * v;
      step2 = std::max(step2, (h * v).squaredNorm());
    }
    m.elastic[ci]->begin(s);
  }
  return step2;
}

// Elastic iterations, inner garments first; outer garments' supports load
// the inner ones through `reactions` (one iteration behind).
void Solver::elastic_iterations(bool body) {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  for (int it = 0; it < c.iterations; ++it) {
    std::swap(m.reactions, m.next_reactions);
    for (Vec3s& r : m.next_reactions) std::fill(r.begin(), r.end(), Vec3::Zero());
    for (int ci : m.order) {
      Cloth::State& s = cloths_[ci].state_;
      detail::ProjectiveSystem& system = *m.elastic[ci];
      const std::vector<double>& weights = system.attachment_weights();
      std::vector<std::uint8_t>& claimed = m.claimed[ci];
      std::fill(claimed.begin(), claimed.end(), 0);
      Vec3s& rhs = m.rhs[ci];
      rhs = m.reactions[ci];
      if (body) m.body.aim_supports(s, m.body_memory[ci], weights, c.body_thickness, rhs, claimed);
      detail::LayerContact::aim_supports(s, m.layer_memory[ci], weights, cloths_, c.layer_thickness, rhs, claimed);
      // Attached in the matrix but no longer supported: follow inertia.
      const Vec3s& y = system.predicted();
      for (std::size_t i = 0; i < rhs.size(); ++i) {
        if (weights[i] != 0.0 && !claimed[i]) rhs[i] += weights[i] * y[i];
      }
      system.iterate(cloths_[ci], s, rhs);
      if (body) m.body.record_supports(s, m.body_memory[ci], weights, claimed);
      detail::LayerContact::record_supports(s, m.layer_memory[ci], weights, cloths_, m.next_reactions);
    }
  }
}

// The fold cap before the strain cap, which then takes up the stretch its
// pushes leave.
void Solver::cap_folds_and_strain() {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  if (c.max_fold > 0) {
    for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
      m.folds[ci].apply(cloths_[ci], cloths_[ci].state_, c.max_fold * kPi / 180, kFoldSweeps);
    }
  }
  if (c.max_strain > 0) {
    for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
      m.limiters[ci].apply(cloths_[ci], cloths_[ci].state_, c.max_strain, 2);
    }
  }
}

// Contact projections: layers (two-way), self, the body, and last the outer
// layers once more against the inner ones (one-way, settle_outer_layers),
// so that a body push on an inner garment cannot leave the layers crossed.
// Each adds what it moved a vertex by to `push` (update_velocities).
void Solver::project_layer_contacts() {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  for (auto& lm : m.layer_memory) lm.forget_touching();
  m.layers.set_guarded(c.collision_pass);
  for (Vec3s& p : m.push) std::fill(p.begin(), p.end(), Vec3::Zero());
  for_each_layer_pair([&](int a, int b, double mu) {
    m.layers.collide(a, cloths_[a], cloths_[a].state_, m.layer_memory[a], b, cloths_[b], cloths_[b].state_,
                     m.layer_memory[b], m.body_memory[a].touching, c.layer_thickness, mu, m.push[a], m.push[b]);
    if (!(c.layer_edge_thickness > 0)) return;
    // The pair's edges (outer, inner) from the shared candidates.
    m.ensure_candidates(cloths_, c, has_body());
    m.layers.collide_edges(cloths_[a], cloths_[a].state_, cloths_[b], cloths_[b].state_, c.layer_edge_thickness,
                           m.candidates.layer_edge_pairs(a, b), m.push[a], m.push[b]);
  });
}

void Solver::project_self_contacts() {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  if (!c.self_contact) return;
  for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
    Cloth& cloth = cloths_[ci];
    if (cloth.self_contact()) {
      m.self.collide(cloth, cloth.state_, c.self_thickness, cloth.material().self_friction, m.push[ci]);
    }
  }
}

// The body's vertex-face and edge-edge pushes; body_push[ci] says how far
// the body moved garment ci.
void Solver::project_body_contacts(bool body, double body_edges, double h) {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  std::vector<double>& body_push = m.body_push;
  body_push.assign(cloths_.size(), 0.0);
  if (!body) return;
  for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
    Cloth::State& s = cloths_[ci].state_;
    body_push[ci] = m.body.collide(s, m.body_memory[ci], c.body_thickness, cloths_[ci].material().friction, h);
    if (!(body_edges > 0)) continue;
    // This garment's edges against the body's, from the shared candidates.
    m.ensure_candidates(cloths_, c, true);
    body_push[ci] = std::max(body_push[ci], m.body.collide_edges(cloths_[ci], s, body_edges, m.push[ci],
                                                                 m.candidates.body_edge_pairs(static_cast<int>(ci))));
  }
}

void Solver::settle_outer_layers() {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  for_each_layer_pair([&](int a, int b, double mu) {
    // Only needed where the body moved the inner garment noticeably.
    if (m.body_push[a] < 0.05 * c.layer_thickness) return;
    m.layers.settle_outer(a, cloths_[a], cloths_[a].state_, cloths_[b], cloths_[b].state_, m.layer_memory[b],
                          c.layer_thickness, mu, m.push[b]);
  });
}

// The strain cap once more: contact pushes can stretch edges near
// contacts. Vertices in contact stay where the contacts put them (the free
// end of an edge moves), so the cap cannot push them back through.
void Solver::recap_strain(bool body) {
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  if (!(c.max_strain > 0)) return;
  for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
    const std::vector<std::uint8_t>& on_body = m.body_memory[ci].touching;
    const std::vector<std::uint8_t>& on_layer = m.layer_memory[ci].touching;
    m.held.assign(cloths_[ci].state_.x.size(), 0);
    for (std::size_t i = 0; i < m.held.size(); ++i) {
      m.held[i] = (body && on_body[i]) || on_layer[i];
    }
    timings_.cap_sweeps +=
        m.limiters[ci].apply(cloths_[ci], cloths_[ci].state_, c.max_strain, c.strain_sweeps, &m.held);
    if (!m.limiters[ci].converged()) ++timings_.cap_unfinished;
  }
}

// Velocities from the position change, except that cloth-cloth pushes move
// positions without adding velocity: they only remove the part of the
// velocity that approached the contact (inelastic). Otherwise an overlap
// left from an earlier substep would launch the layers apart.
void Solver::update_velocities(double h) {
  Impl& m = *impl_;
  const double inv_h = 1.0 / h;
  for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
    Cloth::State& s = cloths_[ci].state_;
    const Vec3s& push = m.push[ci];
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (s.inv_mass[i] == 0.0 || m.reverted[ci][i]) {
        s.v[i] = Vec3::Zero();
        continue;
      }
      Vec3 v = (s.x[i] - s.x_start[i] - push[i]) * inv_h;
      const double len = push[i].norm();
      if (len > 0) {
        const Vec3 n = push[i] / len;
        v -= std::min(0.0, v.dot(n)) * n;
      }
      s.v[i] = v;
    }
  }
}

void Solver::collision_pass(bool body) {
  // The pass (collision_pass.h), then up to kCapAfterPass rounds of the
  // strain cap with the vertices the pass moved held and the pass again on
  // what the cap moved: the pass always has the last word.
  Impl& m = *impl_;
  const SolverConfig& c = config_;
  for (auto& r : m.reverted) std::fill(r.begin(), r.end(), 0);
  m.states.clear();
  for (Cloth& cloth : cloths_) m.states.push_back(&cloth.state_);
  detail::SweptBody swept;
  if (body) {
    swept.start = &m.body.pose_before();
    swept.end = &m.body.pose_now();
    swept.faces = &m.body.topology().faces;
    swept.edges = &m.body.edges();
    swept.frame_start = &m.body.frame_start();
    swept.frame_end = &m.body.frame_end();
    swept.frame = m.body.sweep_revision();
    swept.pinch = m.pinch_now;
  }
  for (std::size_t ci = 0; ci < cloths_.size(); ++ci) m.before_pass[ci] = cloths_[ci].state_.x;
  const detail::CollisionPassStats ps =
      m.pass.run(cloths_, m.states, swept, c.collision_gap, c.collision_rounds, m.push, m.reverted);
  timings_.pass_pairs += ps.pairs;
  timings_.pass_reverted += ps.reverted;
  timings_.pass_zoned += ps.zoned;
  long yielded = ps.yielded;
  // The pass's pushes can stretch edges next to the vertices it moved:
  // the strain cap once more with those vertices held, then the pass
  // again on what the cap moved (kCapAfterPass times at most).
  bool again = c.max_strain > 0 && ps.pairs > 0;
  for (int round = 0; again && round < kCapAfterPass; ++round) {
    again = false;
    for (std::size_t ci = 0; ci < cloths_.size(); ++ci) {
      Cloth::State& s = cloths_[ci].state_;
      m.before_cap[ci] = s.x;
      m.held.assign(s.x.size(), 0);
      for (std::size_t i = 0; i < s.x.size(); ++i) m.held[i] = m.reverted[ci][i] || s.x[i] != m.before_pass[ci][i];
      m.limiters[ci].apply(cloths_[ci], s, c.max_strain, c.strain_sweeps, &m.held);
      m.moved[ci].assign(s.x.size(), 0);
      for (std::size_t i = 0; i < s.x.size(); ++i) {
        if (s.x[i] == m.before_cap[ci][i]) continue;
        m.moved[ci][i] = 1;
        again = true;
      }
      m.before_pass[ci] = s.x;
    }
    if (!again) break;
    const detail::CollisionPassStats more =
        m.pass.run(cloths_, m.states, swept, c.collision_gap, c.collision_rounds, m.push, m.reverted, &m.moved);
    timings_.pass_pairs += more.pairs;
    timings_.pass_reverted += more.reverted;
    timings_.pass_zoned += more.zoned;
    yielded = more.yielded;
    again = more.pairs > 0;
  }
  timings_.pass_yielded += yielded;
}

}  // namespace layers::sim
