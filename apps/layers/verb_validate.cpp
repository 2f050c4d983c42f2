// `layers validate`: every schema problem of a dataset, one per line;
// exit 1 if there is any. With --physics, also the generator's validation
// measures recomputed from the stored frames of every sequence (H- and
// L-penetration, exact H- and L-crossings, stretch, non-finite values)
// beside the evaluation's two L-collisions, the body's own crossings, its
// pinch zones and the H-crossing outside and inside them (docs/metrics.md),
// then their spread over the sequences and how
// many frames and sequences meet the crossing target; exit 1 if a
// sequence is over the generator's thresholds. --frames-csv also writes
// every frame's measures, to find where in a sequence they rise;
// --threads measures several sequences at once. --record-hashes migrates a
// dataset written before content hashes: it validates it (the hashes it
// has already are checked) and then records them in dataset.yaml.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>
#include <vector>

#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/parallel.h"

#include "layers/data/content_hash.h"
#include "layers/data/dataset.h"
#include "layers/data/validate.h"
#include "layers/generate/physics_summary.h"
#include "layers/generate/stored_measures.h"
#include "layers/metrics/measures.h"
#include "verbs.h"

namespace layers::app {
namespace {

// The evaluation's two L-collisions of one frame (zoo metrics, nearest
// inner vertex): the paper's plain rule and ours with the open-edge rule;
// NaN without an inner and an outer layer.
struct EvalLCollision {
  double plain = std::nan(""), ours = std::nan("");
};
EvalLCollision eval_l_collision(const generate::StoredFrame& f) {
  std::vector<geometry::TriMesh> inner, outer;
  for (const sim::MeasuredGarment& g : f.garments) (g.outer ? outer : inner).push_back({g.positions, g.faces});
  if (inner.empty() || outer.empty()) return {};
  const geometry::TriMesh inner_mesh = geometry::concatenate(inner);
  const geometry::Points outer_points = geometry::concatenate(outer).vertices;
  const metrics::LCollisionRates l = metrics::l_collision_rates(outer_points, inner_mesh);
  return {l.plain, l.ours};
}

// Mean of the frames' values that are not NaN (NaN when there are none).
struct MeanOfFinite {
  double sum = 0;
  int count = 0;
  void add(double v) {
    if (std::isnan(v)) return;
    sum += v;
    ++count;
  }
  double mean() const { return count > 0 ? sum / count : std::nan(""); }
};

// One stored frame's measures, and a sequence's.
struct MeasuredFrame {
  std::int64_t index = 0;
  sim::FrameMeasures measures;
  EvalLCollision l;
};
struct MeasuredSequence {
  std::vector<MeasuredFrame> frames;
};

// The per-frame table of --frames-csv, in percent like the printed one.
class FramesCsv {
 public:
  FramesCsv() {
    text_ << "sequence,frame,h_penetration_pct,l_penetration_pct,h_crossing_pct,l_crossing_pct,h_crossing_pairs,"
             "l_crossing_pairs,cloth_crossing_pairs,body_self_crossing_pct,body_pinch_pct,h_crossing_clear_pct,h_"
             "crossing_pinch_pct,max_stretch_pct,l_collision_paper_pct,l_collision_ours_pct\n";
  }
  void add(const std::string& id, std::int64_t frame, const sim::FrameMeasures& m, const EvalLCollision& l) {
    text_ << id << ',' << frame;
    for (double v : {m.h_penetration, m.l_penetration, m.h_crossing, m.l_crossing}) percent(v);
    text_ << ',' << m.h_crossing_pairs << ',' << m.l_crossing_pairs << ',' << m.cloth_crossing_pairs;
    for (double v :
         {m.body_self_crossing, m.body_pinch, m.h_crossing_clear, m.h_crossing_pinch, m.max_stretch, l.plain, l.ours})
      percent(v);
    text_ << '\n';
  }
  std::string text() const { return text_.str(); }

 private:
  // A value that was not measured (NaN) is an empty field.
  void percent(double v) {
    text_ << ',';
    if (!std::isnan(v)) text_ << 100 * v;
  }
  std::ostringstream text_;
};

// --frames-csv names a new file: nothing a user made is overwritten.
constexpr const char* kFramesCsvExists = "exists; --frames-csv must name a new file (nothing is overwritten)";

int check_physics(const std::string& path, const sim::ValidationConfig& limits, double crossing_target,
                  const std::string& frames_csv, int threads) {
  const data::Dataset dataset = data::Dataset::open(path);
  std::optional<FramesCsv> frames;  // only when asked for
  if (!frames_csv.empty()) frames.emplace();
  generate::PhysicsSummary summary(crossing_target);
  sim::SequenceMeasures all;
  MeanOfFinite all_ours, all_plain;
  int over = 0;
  std::printf("%-14s %6s %9s %9s %13s %12s %9s %9s %9s %9s %8s %9s %9s %9s %9s %9s  %s\n", "sequence", "frames",
              "H-pen", "L-pen", "L-coll(paper)", "L-coll(ours)", "H-x mean", "H-x max", "L-x mean", "L-x max",
              "cloth-x", "body-self", "pinch", "H-x clear", "H-x pinch", "stretch", "verdict");
  // Sequences are measured `threads` at a time (the Dataset serialises its
  // HDF5 reads) and reported in the dataset's order after each such batch.
  const std::vector<std::string> ids = dataset.ids();
  const std::size_t batch = static_cast<std::size_t>(std::max(threads, 1));
  std::vector<MeasuredSequence> batch_results;
  for (std::size_t k = 0; k < ids.size(); ++k) {
    if (k % batch == 0) {
      const std::size_t first = k;
      batch_results.assign(std::min(batch, ids.size() - k), {});
      parallel_indices(batch_results.size(), threads, [&](std::size_t j) {
        const data::SequenceData seq = dataset.read_sequence(ids[first + j]);
        generate::for_each_stored_frame(seq, [&](std::int64_t index, const generate::StoredFrame& f) {
          batch_results[j].frames.push_back(
              {index, sim::measure_frame(f.body, f.garments, limits.l_reach, true, limits.pinch_distance),
               eval_l_collision(f)});
        });
      });
    }
    const std::string& id = ids[k];
    sim::SequenceMeasures m;
    MeanOfFinite ours, plain;
    for (const MeasuredFrame& f : batch_results[k % batch].frames) {
      m.add(f.measures);
      all.add(f.measures);
      summary.add_frame(f.measures);
      ours.add(f.l.ours);
      all_ours.add(f.l.ours);
      plain.add(f.l.plain);
      all_plain.add(f.l.plain);
      if (frames) frames->add(id, f.index, f.measures, f.l);
    }
    const std::vector<std::string> violations = m.violations(limits);
    std::string verdict = violations.empty() ? "ok" : "";
    for (const std::string& v : violations) verdict += (verdict.empty() ? "" : "; ") + v;
    over += !violations.empty();
    std::printf(
        "%-14s %6d %8.3f%% %8.3f%% %12.2f%% %11.2f%% %8.3f%% %8.3f%% %8.3f%% %8.3f%% %8lld %8.3f%% %8.3f%% %8.3f%% "
        "%8.3f%% %8.2f%%  %s\n",
        id.c_str(), m.frames(), 100 * m.mean_h_penetration(), 100 * m.mean_l_penetration(), 100 * plain.mean(),
        100 * ours.mean(), 100 * m.mean_h_crossing(), 100 * m.max_h_crossing(), 100 * m.mean_l_crossing(),
        100 * m.max_l_crossing(), static_cast<long long>(m.max_cloth_crossings()), 100 * m.mean_body_self_crossing(),
        100 * m.mean_body_pinch(), 100 * m.mean_h_crossing_clear(), 100 * m.mean_h_crossing_pinch(),
        100 * m.max_stretch(), verdict.c_str());
    // A sequence without a measurable frame is left out of the spread
    // (SequenceMeasures reads 0 there).
    const auto measured = [&m](double v) { return m.measured() > 0 ? v : std::nan(""); };
    summary.end_sequence({{"H-pen", measured(m.mean_h_penetration())},
                          {"L-pen", measured(m.mean_l_penetration())},
                          {"L-coll(paper)", plain.mean()},
                          {"L-coll(ours)", ours.mean()},
                          {"H-x mean", measured(m.mean_h_crossing())},
                          {"H-x max", measured(m.max_h_crossing())},
                          {"L-x mean", measured(m.mean_l_crossing())},
                          {"L-x max", measured(m.max_l_crossing())},
                          {"body-self", m.mean_body_self_crossing()},
                          {"pinch", m.mean_body_pinch()},
                          {"H-x clear", m.mean_h_crossing_clear()},
                          {"H-x pinch", m.mean_h_crossing_pinch()},
                          {"stretch", measured(m.max_stretch())}});
  }
  std::printf("%s", summary.text().c_str());
  std::printf(
      "%s: %zu sequences, %d frames: mean H-penetration %.3f%%, mean L-penetration %.3f%% (generator rule, reach %.0f "
      "mm), mean L-collision %.2f%% (evaluation, paper's rule) and %.2f%% (evaluation, ours: open-edge rule), "
      "H-crossing mean %.3f%% worst frame %.3f%%, L-crossing mean "
      "%.3f%% worst frame %.3f%%, crossing face pairs between garments (all pairs, and self) worst frame %lld, body "
      "faces crossing the body %.3f%% mean, body faces in pinch zones %.3f%% mean (pinch distance %.0f mm), "
      "H-crossing outside them mean %.3f%% worst frame %.3f%%, inside them mean %.3f%% worst frame %.3f%%, max "
      "stretch %.2f%%, %lld non-finite values; %d over the thresholds (H %.2f%%, L "
      "%.2f%%, H-crossing %.2f%%, H-crossing outside pinch zones %.2f%%, L-crossing %.2f%%, stretch %.0f%%)\n",
      path.c_str(), ids.size(), all.frames(), 100 * all.mean_h_penetration(), 100 * all.mean_l_penetration(),
      1000 * limits.l_reach, 100 * all_plain.mean(), 100 * all_ours.mean(), 100 * all.mean_h_crossing(),
      100 * all.max_h_crossing(), 100 * all.mean_l_crossing(), 100 * all.max_l_crossing(),
      static_cast<long long>(all.max_cloth_crossings()), 100 * all.mean_body_self_crossing(),
      100 * all.mean_body_pinch(), 1000 * limits.pinch_distance, 100 * all.mean_h_crossing_clear(),
      100 * all.max_h_crossing_clear(), 100 * all.mean_h_crossing_pinch(), 100 * all.max_h_crossing_pinch(),
      100 * all.max_stretch(), static_cast<long long>(all.nonfinite()), over, 100 * limits.max_h_penetration,
      100 * limits.max_l_penetration, 100 * limits.max_h_crossing, 100 * limits.max_h_crossing_clear,
      100 * limits.max_l_crossing, 100 * limits.max_stretch);
  if (frames) {
    write_new_text_file(frames_csv, frames->text(), kFramesCsvExists);
    std::printf("per-frame measures: %s\n", frames_csv.c_str());
  }
  return over == 0 ? static_cast<int>(kOk) : static_cast<int>(kFailure);
}

}  // namespace

VerbRun register_validate(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("validate",
                                 "Check a dataset folder or shard file against LAYERS-H5 v1; exit 1 on any problem");
  auto path = std::make_shared<std::string>();
  auto physics = std::make_shared<bool>(false);
  auto limits = std::make_shared<sim::ValidationConfig>();
  auto target = std::make_shared<double>(0.1);
  auto frames_csv = std::make_shared<std::string>();
  auto threads = std::make_shared<int>(1);
  auto record = std::make_shared<bool>(false);
  cmd->add_option("path", *path, "dataset folder or shard .h5 file")->required();
  cmd->add_flag("--record-hashes", *record,
                "for a dataset folder written before content hashes: validate it, then record its shard list, "
                "sequence and stats hashes in dataset.yaml (the migration; docs/format.md)");
  cmd->add_flag("--physics", *physics,
                "also recompute the generator's validation measures from the stored frames (H/L-penetration, "
                "stretch; slow: every frame of every sequence)");
  cmd->add_option("--l-reach", limits->l_reach, "L-penetration reach in metres (generator default 0.03)");
  cmd->add_option("--pinch-distance", limits->pinch_distance,
                  "pinch zones: body vertices closer than this (metres) to a body vertex that is not their neighbour "
                  "along the mesh (default 0.018)")
      ->check(CLI::Range(0.0, 0.2));
  cmd->add_option("--crossing-target", *target,
                  "with --physics: count the frames whose H- and L-crossing are at most this percentage")
      ->check(CLI::Range(0.0, 100.0));
  cmd->add_option("--frames-csv", *frames_csv,
                  "with --physics: also write every frame's measures (one row per sequence and frame, in percent) "
                  "to this new file");
  cmd->add_option("--threads", *threads, "with --physics: sequences measured at once (the output is the same)")
      ->capture_default_str()
      ->check(CLI::Range(1, 256));
  return [path, physics, limits, target, frames_csv, threads, record]() {
    if (!frames_csv->empty() && !*physics) throw UsageError("--frames-csv needs --physics");
    if (*record && *physics) throw UsageError("--record-hashes and --physics are run separately");
    if (*record && !std::filesystem::is_directory(*path))
      throw UsageError("--record-hashes needs a dataset folder (a shard file records its own hashes when written)");
    if (*threads != 1 && !*physics) throw UsageError("--threads needs --physics");
    std::error_code ec;
    if (!frames_csv->empty() && std::filesystem::exists(*frames_csv, ec))
      throw InputError::message(*frames_csv, "", kFramesCsvExists);
    data::ValidateOptions options;
    options.allow_unhashed = *record;
    auto problems = data::validate_dataset(*path, options);
    for (const auto& p : problems) std::printf("%s\n", p.to_string().c_str());
    if (!problems.empty()) {
      std::printf("%s: %zu problem%s%s\n", path->c_str(), problems.size(), problems.size() == 1 ? "" : "s",
                  *record ? "; no hash recorded" : "");
      return static_cast<int>(kFailure);
    }
    std::printf("%s: valid LAYERS-H5 (format version 1)\n", path->c_str());
    if (*record) {
      data::record_integrity(*path);
      std::printf("%s: shard list, content hashes and stats hash recorded in dataset.yaml\n", path->c_str());
      return static_cast<int>(kOk);
    }
    return *physics ? check_physics(*path, *limits, *target / 100, *frames_csv, *threads) : static_cast<int>(kOk);
  };
}

}  // namespace layers::app
