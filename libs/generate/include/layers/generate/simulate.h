// layers/generate/simulate.h -- one scene from spec to LAYERS-H5 sequence:
// body and motion, garments fitted in the T-pose, drape (warm-up) in the
// T-pose, blend into the motion, record frame by frame with the cloth
// solver, validate.
#pragma once

#include <Eigen/Geometry>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "layers/data/sequence.h"
#include "layers/garment/garment_body.h"
#include "layers/garment/garment_pieces.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"
#include "layers/motion/body_config.h"
#include "layers/sim/solver.h"

namespace layers::generate {

// Whether a garment of this type gets self-contact in the solver (folds
// of skirts, dresses and hoods; `layers crosscheck` gives Blender's
// separate cloths the same).
bool wants_self_contact(const std::string& type);
// A stored garment's self-contact: its attribute `self_contact` (1 or 0,
// written for imported garments from their side file), else its type's.
inline constexpr const char* kSelfContact = "self_contact";
bool garment_self_contact(const data::GarmentStatic& garment);

struct SceneResult {
  bool ok = false;
  data::SequenceData sequence;          // when ok
  std::vector<std::string> violations;  // why it was skipped, when not ok
  double mean_h_penetration = 0, mean_l_penetration = 0, max_stretch = 0;
  double max_h_crossing = 0, max_l_crossing = 0;  // worst frame
  int simulated_frames = 0;                       // warm-up included
  int recorded_frames = 0;  // recorded frames simulated: config.frames, or up to a clean window's cut
  int stored_frames = 0;    // frames of `sequence` (when ok)
  int cut_frame = -1;       // clean windows: the first recorded frame that broke a per-frame rule; -1: none
  std::string rule;         // the rule that cost frames (sim::Violation::rule, or "unusable"); "" when none did
  double seconds = 0;       // wall clock
  double cpu_seconds = 0;   // CPU time of the simulating thread
};

// Called after every simulated frame when given (diagnostics, pictures):
// the phase ("drape", "blend" or "record"), the frame index within it and
// the solver, whose body and cloths are at the end of that frame.
using FrameObserver = std::function<void(const char* phase, int frame, const sim::Solver& solver)>;

// A scene ready to simulate: the body motion (T-pose blending into the
// motion, then the recorded frames), the outfit fitted around the T-pose
// body and moved to where the motion starts, and the solver holding both.
// Timeline: config.drape_frames in the T-pose (gravity ramped in over the
// first two thirds, extra air damping; not recorded), then
// transition_frames - 1 frames blending into the motion, then
// config.frames recorded frames, each one solver step of 1/30 s.
class SceneSimulation {
 public:
  // Throws what the templates, the body model or the solver throw.
  SceneSimulation(const GeneratorConfig& config, const SceneSpec& spec);

  // False when the body self-intersects in frames that could not be
  // repaired (with clean windows: before window_min_frames recorded
  // frames), or a garment could not be made into a valid cloth;
  // problem() says why. Nothing can be simulated then.
  bool usable() const { return problem_.empty(); }
  const std::string& problem() const { return problem_; }

  // Drape and blend (no wind).
  void warm_up(const FrameObserver& observer = {});
  // Advances to recorded frame r with its scheduled wind (r = 0, 1, ...
  // in order, after warm_up()).
  void record(int r);
  int warm_up_frames() const;
  // config.frames, or fewer with clean windows (window_min_frames > 0)
  // when the body crosses itself beyond repair from a later frame: the
  // frames before it.
  int recorded_frames() const { return recordable_; }

  const sim::Solver& solver() const { return solver_; }
  sim::Solver& solver() { return solver_; }
  const sim::WindSchedule& wind() const { return wind_; }
  const motion::GeneratedBody& body() const { return generated_; }
  // The garments' arrays (rest shapes as simulated, no positions).
  std::vector<data::GarmentData>& garments() { return garments_; }
  // The rigid motion that took the T-pose garments to the motion's start.
  const Eigen::Isometry3d& placement() const { return place_; }

 private:
  geometry::Points body_frame(int frame) const;
  // The room the motion asks of the garments, as configured (garment_leg_room.h).
  garment::MotionRoom motion_room(const garment::TPoseBody& t_pose) const;
  void add_garments();

  GeneratorConfig config_;
  SceneSpec spec_;
  std::string problem_;
  int recordable_ = 0;
  motion::GeneratedBody generated_;
  std::vector<data::GarmentData> garments_;
  Eigen::Isometry3d place_ = Eigen::Isometry3d::Identity();
  sim::WindSchedule wind_;
  sim::Solver solver_;
};

// CPU seconds used by the calling thread so far (how scenes are timed).
double thread_cpu_seconds();

// Never writes anything; a scene over its thresholds comes back with
// ok = false and the reasons. With `keep_refused`, a refused scene's
// `sequence` holds its recorded frames too (up to and including the frame
// that broke a rule, or every frame), to be looked at.
SceneResult simulate_scene(const GeneratorConfig& config, const SceneSpec& spec, const FrameObserver& observer = {},
                           bool keep_refused = false);

}  // namespace layers::generate
