// One scene, simulated (see simulate.h). Timeline: `drape_frames` with the
// body standing in its T-pose (the garments settle under gravity ramped in,
// with extra damping; not recorded), then
// `transition_frames` blending from the T-pose into the motion, then the
// recorded frames, each one solver step of 1/30 s.
#include "layers/generate/simulate.h"

#include <spdlog/spdlog.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "layers/core/error.h"
#include "layers/core/progress.h"
#include "layers/generate/body_data.h"
#include "layers/generate/outfit.h"
#include "layers/scene/body_sequence.h"
#include "layers/scene/motion.h"
#include "layers/sim/measures.h"
#include "layers/sim/solver.h"

namespace layers::generate {
namespace {

geometry::Points frame_points(const std::vector<float>& positions, int frame, int n) {
  geometry::Points p(n, 3);
  std::copy(positions.begin() + static_cast<std::ptrdiff_t>(frame) * n * 3,
            positions.begin() + static_cast<std::ptrdiff_t>(frame + 1) * n * 3, p.data());
  return p;
}

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

bool wants_self_contact(const std::string& type) {
  return type == "skirt" || type == "dress" || type == "dress_belt" || type == "jacket_hood";
}

}  // namespace

SceneResult simulate_scene(const GeneratorConfig& config, const SceneSpec& spec) {
  Timer timer;
  SceneResult result;
  const int drape = config.drape_frames, blend = config.body.transition_frames, record = config.frames;

  // Body: the T-pose blending into the motion, then the recorded frames.
  scene::BodyMotionConfig body_config;
  body_config.shape = spec.shape;
  body_config.motion = spec.motion;
  body_config.frames = blend + record;
  body_config.transition_frames = blend;
  body_config.seed = spec.seed;
  body_config.intersection_tolerance_mm = config.body.intersection_tolerance_mm;
  body_config.on_intersection = "longest_run";
  scene::GeneratedBody generated = scene::generate_body(body_config);
  const scene::BodySequence& motion = generated.sequence;
  if (motion.num_frames < blend + record || motion.source_frame.front() != 0) {
    result.violations.push_back("the body self-intersects in frames that could not be repaired (" +
                                std::to_string(motion.num_frames) + " of " + std::to_string(blend + record) +
                                " frames usable)");
    result.seconds = timer.seconds();
    return result;
  }
  const int nb = motion.num_vertices;
  const scene::BodyArrays body_arrays = scene::body_arrays(generated.body);
  geometry::TriMesh body;
  body.faces = Eigen::Map<const geometry::Faces>(body_arrays.faces.data(),
                                                 static_cast<Eigen::Index>(body_arrays.faces.size() / 3), 3);
  body.vertices = frame_points(motion.positions, 0, nb);

  // Garments fitted around the T-pose body, moved to where the motion starts.
  std::vector<data::GarmentData> garments = fit_outfit(generated.body, spec, config.garments.fit);
  const scene::BodyFrame t_pose = scene::pose_body(generated.body, generated.body.t_pose);
  const Eigen::Isometry3d place = rigid_fit(t_pose.vertices, body.vertices);

  sim::Solver solver(config.sim);
  for (auto& g : garments) {
    geometry::TriMesh rest;
    rest.vertices = (place * rows(g.rest).cast<double>().transpose()).transpose().cast<float>();
    rest.faces = Eigen::Map<const geometry::Faces>(g.faces.data(), static_cast<Eigen::Index>(g.faces.size() / 3), 3);
    std::copy(rest.vertices.data(), rest.vertices.data() + rest.vertices.size(), g.rest.begin());
    sim::ClothOptions options;
    options.name = g.name;
    options.layer = g.layer;
    options.self_contact = wants_self_contact(g.type);
    options.uv = Eigen::Map<const sim::UVs>(g.uv.data(), static_cast<Eigen::Index>(g.uv.size() / 2), 2);
    options.uv_faces =
        Eigen::Map<const geometry::Faces>(g.uv_faces.data(), static_cast<Eigen::Index>(g.uv_faces.size() / 3), 3);
    const std::string what = spec.id + " " + g.name;
    solver.add_cloth(sim::Cloth(rest, sim::to_material(garment_attributes(g.attributes, what), {}, what), options));
  }
  solver.set_body(body);

  // Warm-up: settle in the T-pose, then blend into the motion (no wind).
  // Gravity is ramped in over the first two thirds of the drape, with
  // extra air damping, so that the garments fitted around the T-pose sink
  // onto the shoulders gently instead of dropping onto them (a sudden drop
  // overstretches edges around the neck, shoulders and armpits, and
  // squeezes outer vertices through the inner garments there).
  const int ramp = std::max(1, 2 * drape / 3);
  for (int f = 0; f < drape; ++f) {
    sim::SolverConfig settle = config.sim;
    const double share = std::min(1.0, (f + 1.0) / ramp);
    for (double& g : settle.gravity) g *= share;
    settle.air_damping = std::max(config.sim.air_damping, kDrapeDamping);
    solver.set_config(settle);
    solver.step();
  }
  solver.set_config(config.sim);
  for (int f = 1; f < blend; ++f) solver.step(frame_points(motion.positions, f, nb));

  // Recorded frames.
  sim::WindSchedule schedule(spec.wind);
  sim::SequenceMeasures measures;
  for (auto& g : garments) g.positions.resize(static_cast<std::size_t>(record) * g.rest.size());
  data::SequenceData& seq = result.sequence;
  seq.wind.rotation.resize(static_cast<std::size_t>(record) * 4);
  seq.wind.strength.resize(static_cast<std::size_t>(record));
  for (int r = 0; r < record; ++r) {
    const sim::Wind wind = schedule.at(r);
    solver.step(frame_points(motion.positions, blend + r, nb), wind);
    measures.add(sim::measure_frame(solver));
    for (std::size_t k = 0; k < garments.size(); ++k) {
      geometry::Points p = solver.cloth(static_cast<int>(k)).positions();
      std::copy(p.data(), p.data() + p.size(), garments[k].positions.begin() + static_cast<std::ptrdiff_t>(r) * p.size());
    }
    Eigen::Vector4d q = wind.rotation();
    for (int c = 0; c < 4; ++c) seq.wind.rotation[static_cast<std::size_t>(r) * 4 + c] = static_cast<float>(q[c]);
    seq.wind.strength[r] = static_cast<float>(wind.strength);
  }
  result.simulated_frames = drape + blend - 1 + record;
  result.mean_h_penetration = measures.mean_h_penetration();
  result.mean_l_penetration = measures.mean_l_penetration();
  result.max_stretch = measures.max_stretch();
  result.violations = measures.violations(config.sim.validation);
  result.ok = result.violations.empty();
  result.seconds = timer.seconds();
  spdlog::debug("{}: {} frames in {:.1f} s, H-pen {:.3f}%, L-pen {:.3f}%, stretch {:.3f}", spec.id,
                result.simulated_frames, result.seconds, 100 * result.mean_h_penetration,
                100 * result.mean_l_penetration, result.max_stretch);
  if (!result.ok) return result;

  seq.id = spec.id;
  seq.seed = spec.seed;
  seq.tags = spec.tags;
  fill_body(seq, generated, blend, record);
  seq.motion = motion.motion;
  seq.garments = std::move(garments);
  return result;
}

}  // namespace layers::generate
