// One scene, simulated (see simulate.h): SceneSimulation sets the scene up
// and steps it; simulate_scene() records, validates and fills the
// LAYERS-H5 sequence.
#include "layers/generate/simulate.h"

#include "layers/data/format.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <cmath>
#include <ctime>

#include "layers/body/body_arrays.h"
#include "layers/core/error.h"
#include "layers/core/progress.h"
#include "layers/garment/garment_leg_room.h"
#include "layers/generate/body_data.h"
#include "layers/generate/imported_garment.h"
#include "layers/generate/outfit.h"
#include "layers/generate/own_body.h"
#include "layers/geometry/intersect.h"
#include "layers/geometry/normals.h"
#include "layers/motion/body_sequence.h"
#include "layers/motion/motion.h"
#include "layers/sim/measures.h"

namespace layers::generate {
namespace {

geometry::Points rows(const std::vector<float>& flat) {
  geometry::Points p(static_cast<Eigen::Index>(flat.size() / 3), 3);
  std::copy(flat.begin(), flat.end(), p.data());
  return p;
}

// The rigid motion taking `from` onto `to` (same vertices), least squares.
Eigen::Isometry3d rigid_fit(const geometry::Points& from, const geometry::Points& to) {
  Eigen::Matrix3Xd a = from.cast<double>().transpose(), b = to.cast<double>().transpose();
  return Eigen::Isometry3d(Eigen::umeyama(a, b, false));
}

// Air damping (1/s) while the garments settle in the T-pose (not recorded).
constexpr double kDrapeDamping = 5.0;

motion::GeneratedBody make_body(const GeneratorConfig& config, const SceneSpec& spec) {
  if (config.body.own) return own_body(config, spec);
  motion::BodyMotionConfig body;
  body.shape = spec.shape;
  body.motion = spec.motion;
  body.frames = config.body.transition_frames + config.frames;
  body.transition_frames = config.body.transition_frames;
  body.seed = spec.seed;
  body.intersection_tolerance_mm = config.body.intersection_tolerance_mm;
  body.self_gap_mm = config.body.self_gap_mm;
  body.arm_room_mm = config.body.arm_room_mm;
  body.thigh_room_mm = config.body.thigh_room_mm;
  body.skin_untangle = config.body.skin_untangle;
  // With clean windows the motion is kept as asked up to its first frame
  // the repair cannot resolve (the scene is cut there); otherwise the
  // whole window must be clean.
  body.on_intersection = config.window_min_frames > 0 ? "first_run" : "longest_run";
  return motion::generate_body(body);
}

}  // namespace

namespace {

// Garments fitted at a coarse resolution can cross each other where the
// outer garment's flat faces cut the inner one's curve (chords). Each
// round moves the vertices of the higher garment's crossing faces (of
// every crossing pair of different garments; for one layer, the later
// garment) outwards along its vertex normals by `step`; rounds stop when
// nothing crosses. The rest shape moves with them (a garment made that
// much looser). Returns the rounds taken, or -1 if crossings remain.
int separate_fitted_garments(std::vector<data::GarmentData>& garments, int max_rounds, float step) {
  const auto mesh_of = [](const data::GarmentData& g) {
    geometry::TriMesh m;
    m.vertices = Eigen::Map<const geometry::Points>(g.rest.data(), static_cast<Eigen::Index>(g.rest.size() / 3), 3);
    m.faces = Eigen::Map<const geometry::Faces>(g.faces.data(), static_cast<Eigen::Index>(g.faces.size() / 3), 3);
    return m;
  };
  for (int round = 0; round < max_rounds; ++round) {
    bool crossed = false;
    for (std::size_t a = 0; a < garments.size(); ++a) {
      for (std::size_t b = 0; b < garments.size(); ++b) {
        // a moves: it is outside b (higher layer, or later in one layer).
        if (a == b || garments[a].layer < garments[b].layer || (garments[a].layer == garments[b].layer && a < b))
          continue;
        geometry::TriMesh outer = mesh_of(garments[a]);
        std::vector<char> move(static_cast<std::size_t>(outer.num_vertices()), 0);
        bool any = false;
        geometry::visit_crossings(outer, geometry::FaceTree(mesh_of(garments[b])), [&](int f, int) {
          for (int k = 0; k < 3; ++k) move[outer.faces(f, k)] = 1;
          any = true;
        });
        if (!any) continue;
        crossed = true;
        const geometry::Points n = geometry::vertex_normals(outer);
        for (Eigen::Index v = 0; v < outer.num_vertices(); ++v) {
          if (!move[v]) continue;
          for (int k = 0; k < 3; ++k) garments[a].rest[v * 3 + k] += step * n(v, k);
        }
      }
    }
    if (!crossed) return round;
  }
  return -1;
}

}  // namespace

bool wants_self_contact(const std::string& type) {
  const data::GarmentTypeInfo* t = data::find_garment_type(type);
  return t && t->self_contact;
}

bool garment_self_contact(const data::GarmentStatic& garment) {
  const auto it = garment.attributes.find(kSelfContact);
  return it != garment.attributes.end() ? it->second != 0.0 : wants_self_contact(garment.type);
}

SceneSimulation::SceneSimulation(const GeneratorConfig& config, const SceneSpec& spec)
    : config_(config), spec_(spec), generated_(make_body(config, spec)), wind_(spec.wind), solver_(config.sim) {
  const motion::BodySequence& motion = generated_.sequence;
  const motion::IntersectionReport& ir = motion.intersection;
  if (ir.arm_room.frames > 0) spdlog::debug("{}: arm room: {}", spec_.id, ir.arm_room.describe("arms", ir.frames));
  if (ir.thigh_room.frames > 0)
    spdlog::debug("{}: thigh room: {}", spec_.id, ir.thigh_room.describe("legs", ir.frames));
  if (config.body.skin_untangle.passes > 0)
    spdlog::debug("{}: skin untangled in {} frames: {} -> {} crossing skin faces", spec_.id, ir.skin_frames,
                  ir.skin_crossing_before, ir.skin_crossing_after);
  const int transition = config_.body.transition_frames;
  const int needed = transition + config_.frames;
  // With clean windows the body may end early (first_run): the frames it
  // allows must still make a window of window_min_frames.
  const bool windows = config_.window_min_frames > 0;
  if (motion.num_frames < (windows ? transition + config_.window_min_frames : needed) ||
      motion.source_frame.front() != 0) {
    problem_ = windows ? "the body self-intersects beyond repair from recorded frame " +
                             std::to_string(std::max(0, motion.num_frames - transition)) +
                             ": the clean window before it has fewer than " +
                             std::to_string(config_.window_min_frames) + " frames (window_min_frames)"
                       : "the body self-intersects in frames that could not be repaired (" +
                             std::to_string(motion.num_frames) + " of " + std::to_string(needed) + " frames usable)";
    return;
  }
  recordable_ = std::min(config_.frames, motion.num_frames - transition);
  const body::BodyArrays body_arrays = body::body_arrays(generated_.body);
  geometry::TriMesh body;
  body.faces = Eigen::Map<const geometry::Faces>(body_arrays.faces.data(),
                                                 static_cast<Eigen::Index>(body_arrays.faces.size() / 3), 3);
  body.vertices = body_frame(0);

  // Garments fitted around the T-pose body, moved to where the motion
  // starts. A garment the templates cannot make into a valid cloth (a
  // degenerate face) makes this scene unusable, not the whole dataset.
  try {
    add_garments();
  } catch (const Error& e) {
    problem_ = std::string("the garments could not be built: ") + e.what();
    return;
  }
  solver_.set_body(body);
  // The collision pass keeps garments from crossing, but cannot untangle
  // garments that start crossed: such a scene is refused here.
  // Each garment with itself (where it has self-contact), then each pair
  // (self-contact off, so that only the pair counts).
  std::string crossings;
  const auto garment = [&](int i, bool self) {
    const sim::Cloth& c = solver_.cloth(i);
    return sim::MeasuredGarment{c.positions(), c.faces(), {}, {}, false, self};
  };
  for (int a = 0; a < solver_.num_cloths(); ++a) {
    for (int b = 0; b <= a; ++b) {
      const std::int64_t n = a == b ? sim::cloth_crossings({garment(a, solver_.cloth(a).self_contact())})
                                    : sim::cloth_crossings({garment(a, false), garment(b, false)});
      if (n == 0) continue;
      crossings += (crossings.empty() ? "" : ", ") + std::to_string(n) + " face pairs of " + solver_.cloth(a).name() +
                   (a == b ? " with itself" : " with " + solver_.cloth(b).name());
    }
  }
  if (!crossings.empty()) problem_ = "the garments cross as fitted, before any simulation (" + crossings + ")";
}

void SceneSimulation::add_garments() {
  if (spec_.garments.empty()) return;  // the body alone (no outfit: `layers tpose`)
  const garment::TPoseBody t_pose = garment::t_pose_body(generated_.body);
  if (has_imported_garments(spec_)) {
    garments_ = imported_outfit(t_pose, spec_, config_.garments.fit.layer_reach, config_.garments.fit.edge_length);
  } else {
    // The room a motion asks of the templates (measured on our body's landmarks).
    const garment::MotionRoom room = motion_room(t_pose);
    garments_ = fit_outfit(t_pose, spec_, config_.garments.fit, &room);
  }
  // Templates fitted at a coarse resolution are moved apart where they
  // cross; a user's garments are taken as they are (crossings refuse the
  // scene below).
  const int rounds = has_imported_garments(spec_) ? 0 : separate_fitted_garments(garments_, 20, 0.002f);
  if (rounds > 0) spdlog::debug("{}: fitted garments separated in {} rounds of 2 mm", spec_.id, rounds);
  place_ = rigid_fit(t_pose.mesh.vertices, body_frame(0));
  for (auto& g : garments_) {
    geometry::TriMesh rest;
    rest.vertices = (place_ * rows(g.rest).cast<double>().transpose()).transpose().cast<float>();
    rest.faces = Eigen::Map<const geometry::Faces>(g.faces.data(), static_cast<Eigen::Index>(g.faces.size() / 3), 3);
    std::copy(rest.vertices.data(), rest.vertices.data() + rest.vertices.size(), g.rest.begin());
    sim::ClothOptions options;
    options.name = g.name;
    options.layer = g.layer;
    options.self_contact = garment_self_contact(g);
    options.uv = Eigen::Map<const sim::UVs>(g.uv.data(), static_cast<Eigen::Index>(g.uv.size() / 2), 2);
    options.uv_faces =
        Eigen::Map<const geometry::Faces>(g.uv_faces.data(), static_cast<Eigen::Index>(g.uv_faces.size() / 3), 3);
    const std::string what = spec_.id + " " + g.name;
    solver_.add_cloth(sim::Cloth(
        rest, sim::to_material(garment_attributes(g.attributes, what), config_.garments.material, what), options));
  }
}

garment::MotionRoom SceneSimulation::motion_room(const garment::TPoseBody& t_pose) const {
  garment::MotionRoom room;
  if (!config_.garments.leg_room && !config_.garments.hip_room) return room;
  // Every frame of the motion in the T-pose's pelvis frame (the root joint,
  // whose rotation is its own local one).
  const motion::BodySequence& motion = generated_.sequence;
  const Eigen::Quaterniond to_t_pose = generated_.body.t_pose.local[0].normalized();
  const Eigen::Vector3d t_pose_root = t_pose.joints[0];
  std::vector<geometry::Points> frames;
  frames.reserve(static_cast<std::size_t>(motion.num_frames));
  for (int f = 0; f < motion.num_frames; ++f) {
    const float* q = motion.root_rot.data() + static_cast<std::ptrdiff_t>(f) * 4;
    const float* r = motion.root.data() + static_cast<std::ptrdiff_t>(f) * 3;
    const Eigen::Quaterniond root(q[0], q[1], q[2], q[3]);
    Eigen::Isometry3d to_pelvis = Eigen::Translation3d(t_pose_root) * (to_t_pose * root.conjugate()) *
                                  Eigen::Translation3d(-Eigen::Vector3d(r[0], r[1], r[2]));
    frames.push_back((to_pelvis * body_frame(f).cast<double>().transpose()).transpose().cast<float>());
  }
  if (config_.garments.leg_room) room.legs = garment::leg_room(t_pose, frames);
  if (config_.garments.hip_room) room.hips = garment::hip_room(t_pose, frames, config_.sim.max_strain);
  return room;
}

geometry::Points SceneSimulation::body_frame(int frame) const {
  return motion::frame_vertices(generated_.sequence, frame);
}

int SceneSimulation::warm_up_frames() const { return config_.drape_frames + config_.body.transition_frames - 1; }

void SceneSimulation::warm_up(const FrameObserver& observer) {
  if (!usable()) throw Error("SceneSimulation::warm_up: " + problem_);
  // Gravity is ramped in over the first two thirds of the drape, with
  // extra air damping, so that the garments fitted around the T-pose sink
  // onto the shoulders gently instead of dropping onto them (a sudden drop
  // overstretches edges around the neck, shoulders and armpits, and
  // squeezes outer vertices through the inner garments there).
  const int drape = config_.drape_frames;
  const int ramp = std::max(1, 2 * drape / 3);
  for (int f = 0; f < drape; ++f) {
    sim::SolverConfig settle = config_.sim;
    const double share = std::min(1.0, (f + 1.0) / ramp);
    for (double& g : settle.gravity) g *= share;
    settle.air_damping = std::max(config_.sim.air_damping, kDrapeDamping);
    solver_.set_config(settle);
    solver_.step();
    if (observer) observer("drape", f, solver_);
  }
  solver_.set_config(config_.sim);
  for (int f = 1; f < config_.body.transition_frames; ++f) {
    solver_.step(body_frame(f));
    if (observer) observer("blend", f, solver_);
  }
}

void SceneSimulation::record(int r) {
  if (!usable()) throw Error("SceneSimulation::record: " + problem_);
  if (r < 0 || r >= recordable_)
    throw Error("SceneSimulation::record: frame " + std::to_string(r) + " outside the " + std::to_string(recordable_) +
                " recorded frames the body allows");
  solver_.step(body_frame(config_.body.transition_frames + r), wind_.at(r));
}

double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

SceneResult simulate_scene(const GeneratorConfig& config, const SceneSpec& spec, const FrameObserver& observer,
                           bool keep_refused) {
  Timer timer;
  const double cpu_start = thread_cpu_seconds();
  SceneResult result;
  SceneSimulation scene(config, spec);
  if (!scene.usable()) {
    result.violations.push_back(scene.problem());
    result.rule = "unusable";
    result.seconds = timer.seconds();
    result.cpu_seconds = thread_cpu_seconds() - cpu_start;
    return result;
  }
  // At trace level, each warm-up frame's crossings (where a tangle is born).
  const bool trace = spdlog::should_log(spdlog::level::trace);
  scene.warm_up([&](const char* phase, int frame, const sim::Solver& solver) {
    if (trace) {
      const sim::FrameMeasures m = sim::measure_frame(solver);
      spdlog::trace("{} {} {}: H-crossing {:.3f}%, L-crossing {:.3f}%, stretch {:.3f}", spec.id, phase, frame,
                    100 * m.h_crossing, 100 * m.l_crossing, m.max_stretch);
    }
    if (observer) observer(phase, frame, solver);
  });

  // Recorded frames, measured as they come: config.frames, or the frames
  // before the body's first one beyond repair (a cut, below).
  const int record = scene.recorded_frames();
  const sim::Solver& solver = scene.solver();
  std::vector<data::GarmentData>& garments = scene.garments();
  sim::SequenceMeasures measures;
  for (auto& g : garments) g.positions.resize(static_cast<std::size_t>(record) * g.rest.size());
  data::SequenceData& seq = result.sequence;
  seq.wind.rotation.resize(static_cast<std::size_t>(record) * 4);
  seq.wind.strength.resize(static_cast<std::size_t>(record));
  const sim::ValidationConfig& limits = config.sim.validation;
  std::vector<sim::Violation> broken;  // clean windows: the rules the cut frame broke
  int recorded = 0;
  const auto keep_frame = [&](int r) {
    for (std::size_t k = 0; k < garments.size(); ++k) {
      geometry::Points p = solver.cloth(static_cast<int>(k)).positions();
      std::copy(p.data(), p.data() + p.size(),
                garments[k].positions.begin() + static_cast<std::ptrdiff_t>(r) * p.size());
    }
    const sim::Wind wind = scene.wind().at(r);
    const Eigen::Vector4d q = wind.rotation();
    for (int c = 0; c < 4; ++c) seq.wind.rotation[static_cast<std::size_t>(r) * 4 + c] = static_cast<float>(q[c]);
    seq.wind.strength[r] = static_cast<float>(wind.strength);
  };
  for (int r = 0; r < record; ++r) {
    scene.record(r);
    recorded = r + 1;
    const sim::FrameMeasures m = sim::measure_frame(solver);
    if (config.window_min_frames > 0) {
      broken = sim::frame_violations(m, limits);
      if (!broken.empty()) {
        // The rest of the scene is discarded: frames 0..r-1 are the window
        // (frame r too when a refused scene is kept to be looked at).
        result.cut_frame = r;
        if (keep_refused) keep_frame(r);
        if (observer) observer("record", r, solver);
        break;
      }
    }
    measures.add(m);
    if (r + 1 == record && record < config.frames) {
      // The next frame's body crosses itself beyond repair: the window ends here.
      result.cut_frame = record;
      broken = {sim::Violation{"body", "the body crosses itself beyond repair in the next frame"}};
    }
    if (trace)
      spdlog::trace(
          "{} record {}: H-crossing {:.3f}% ({:.3f}% outside pinch zones), L-crossing {:.3f}%, stretch {:.3f}", spec.id,
          r, 100 * m.h_crossing, 100 * m.h_crossing_clear, 100 * m.l_crossing, m.max_stretch);
    if (observer) observer("record", r, solver);
    keep_frame(r);
  }
  result.simulated_frames = scene.warm_up_frames() + recorded;
  result.recorded_frames = recorded;
  const int kept = result.cut_frame >= 0 ? result.cut_frame : record;
  result.mean_h_penetration = measures.mean_h_penetration();
  result.mean_l_penetration = measures.mean_l_penetration();
  result.max_stretch = measures.max_stretch();
  result.max_h_crossing = measures.max_h_crossing();
  result.max_l_crossing = measures.max_l_crossing();
  // The window's rules (the whole scene's without a cut).
  const std::vector<sim::Violation> window = measures.broken(limits);
  for (const sim::Violation& v : window) result.violations.push_back(v.sentence);
  if (!window.empty()) result.rule = window.front().rule;
  if (result.cut_frame >= 0) {
    std::string why;
    for (const sim::Violation& v : broken) why += (why.empty() ? "" : "; ") + v.sentence;
    if (kept < config.window_min_frames) {
      result.rule = broken.front().rule;
      result.violations.insert(result.violations.begin(),
                               "frame " + std::to_string(result.cut_frame) + " breaks a rule (" + why +
                                   "): the clean window before it has " + std::to_string(kept) +
                                   " frames, fewer than " + std::to_string(config.window_min_frames) +
                                   " (window_min_frames)");
    } else if (window.empty()) {
      result.rule = broken.front().rule;
      spdlog::info("{} cut at recorded frame {} of {} ({}): {} frames kept", spec.id, result.cut_frame, config.frames,
                   why, kept);
    }
  }
  result.ok = result.violations.empty();
  result.seconds = timer.seconds();
  result.cpu_seconds = thread_cpu_seconds() - cpu_start;
  spdlog::debug(
      "{}: {} frames in {:.1f} s ({:.1f} s CPU), H-pen {:.3f}%, L-pen {:.3f}%, worst H-crossing {:.3f}%, worst "
      "L-crossing {:.3f}%, stretch {:.3f} (strain cap out of sweeps in {} calls, one per garment and substep); "
      "collision pass: {:.0f} ms per frame, {} pairs met, {} vertices in impact zones, {} put back, {} body pairs "
      "yielded",
      spec.id, result.simulated_frames, result.seconds, result.cpu_seconds, 100 * result.mean_h_penetration,
      100 * result.mean_l_penetration, 100 * result.max_h_crossing, 100 * result.max_l_crossing, result.max_stretch,
      solver.timings().cap_unfinished, 1e3 * solver.timings().collision_pass / std::max(1L, solver.timings().frames),
      solver.timings().pass_pairs, solver.timings().pass_zoned, solver.timings().pass_reverted,
      solver.timings().pass_yielded);
  if (!result.ok && !keep_refused) return result;

  // A refused scene kept to be looked at: every frame recorded.
  const int stored = result.ok ? kept : recorded;
  if (stored < record) {
    for (auto& g : garments) g.positions.resize(static_cast<std::size_t>(stored) * g.rest.size());
    seq.wind.rotation.resize(static_cast<std::size_t>(stored) * 4);
    seq.wind.strength.resize(static_cast<std::size_t>(stored));
  }
  if (result.ok) result.stored_frames = kept;
  seq.id = spec.id;
  seq.seed = spec.seed;
  seq.tags = spec.tags;
  fill_body(seq, scene.body(), config.body.transition_frames, stored, scene.placement());
  seq.motion = scene.body().sequence.motion;
  seq.garments = std::move(garments);
  return result;
}

}  // namespace layers::generate
