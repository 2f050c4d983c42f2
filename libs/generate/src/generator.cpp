// The dataset loop of `layers generate`: resume, shards, threads, merging
// parts into shards, and the final manifest, splits and statistics (see
// generator.h).
#include "layers/generate/generator.h"

#include <spdlog/spdlog.h>

#include <filesystem>
#include <map>
#include <mutex>
#include <set>
#include <sstream>

#include "layers/core/atomic_file.h"
#include "layers/core/config_node.h"
#include "layers/core/error.h"
#include "layers/core/parallel.h"
#include "layers/core/progress.h"
#include "layers/core/source_revision.h"
#include "layers/core/text_file.h"
#include "layers/data/content_hash.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/manifest.h"
#include "layers/data/shard_writer.h"
#include "layers/data/splits.h"
#include "layers/data/stats.h"
#include "layers/generate/scene_spec.h"
#include "layers/generate/simulate.h"
#include "refused_where.h"

namespace fs = std::filesystem;

namespace layers::generate {
namespace {

struct Layout {
  fs::path out;
  const GeneratorConfig& config;
  int n_shards() const { return (config.sequences + config.sequences_per_shard - 1) / config.sequences_per_shard; }
  fs::path shard(int j) const { return out / data::shard_file_name(j); }
  fs::path part(const std::string& id) const { return out / "parts" / (id + ".h5"); }
  fs::path skipped(const std::string& id) const { return out / "parts" / (id + ".skipped"); }
  // With clean windows: what became of the scene's recorded frames.
  fs::path outcome(const std::string& id) const { return out / "parts" / (id + ".outcome"); }
  int first(int j) const { return j * config.sequences_per_shard; }
  int end(int j) const { return std::min(config.sequences, (j + 1) * config.sequences_per_shard); }
  bool scene_done(int i) const {
    std::string id = scene_id(i);
    return fs::exists(part(id)) || fs::exists(skipped(id));
  }
};

// Whether a run saved its resolved config in the folder; InputError when
// that config is not `config_yaml`.
bool check_saved_config(const Layout& layout, const std::string& config_yaml) {
  const fs::path saved = layout.out / "generator.yaml";
  if (!fs::exists(saved)) return false;
  if (!same_saved_config(saved.string(), config_yaml))
    throw InputError::message(saved.string(), "",
                              "this dataset folder was started with a different generator config; use the same "
                              "config (and --set values) to resume or finalize, or another --out");
  return true;
}

// The source revision of the generator that started the folder, saved
// beside its config: scenes simulated by different code must not end up in
// one dataset, so a run of another revision is refused. A folder started
// before revisions were recorded is "unknown", which no build matches.
void check_revision(const Layout& layout, bool started_before) {
  const fs::path saved = layout.out / "generator_revision";
  const std::string mine = source_revision();
  if (!fs::exists(saved)) {
    write_text_atomic(saved.string(), std::string(started_before ? "unknown" : mine) + "\n");
    if (!started_before) return;
  }
  std::string theirs = read_text_file(saved.string());
  while (!theirs.empty() && (theirs.back() == '\n' || theirs.back() == '\r')) theirs.pop_back();
  if (theirs != mine)
    throw InputError::message(saved.string(), "",
                              "this dataset folder was started by the generator of revision " + theirs +
                                  " and this build is " + mine +
                                  "; resume or finalize it with that revision's build, or use another --out");
}

// Saves the resolved config and the generator's revision, or checks them
// against those a previous run of this folder saved.
void claim_folder(const Layout& layout, const std::string& config_yaml) {
  check_output_folder(layout.out.string());
  fs::create_directories(layout.out / "parts");
  const bool started_before = check_saved_config(layout, config_yaml);
  if (!started_before) write_text_atomic((layout.out / "generator.yaml").string(), config_yaml);
  check_revision(layout, started_before);
}

// Merges the finished parts of shard j into its shard file (if all its
// scenes are done and it does not exist yet), then removes the parts.
void merge_shard(const Layout& layout, int j) {
  if (fs::exists(layout.shard(j))) return;
  for (int i = layout.first(j); i < layout.end(j); ++i)
    if (!layout.scene_done(i)) return;
  std::vector<data::SequenceData> sequences;
  for (int i = layout.first(j); i < layout.end(j); ++i) {
    fs::path part = layout.part(scene_id(i));
    if (fs::exists(part)) sequences.push_back(data::Dataset::open(part.string()).read_sequence(scene_id(i)));
  }
  data::write_shard(layout.shard(j).string(), sequences);
  for (int i = layout.first(j); i < layout.end(j); ++i) fs::remove(layout.part(scene_id(i)));
}

// A scene's outcome marker (clean windows): recorded frames simulated,
// stored, the cut frame (-1: none) and the rule that cost frames.
struct Outcome {
  std::int64_t recorded = 0, stored = 0, cut = -1;
  std::string rule;
};

void write_outcome(const Layout& layout, const std::string& id, const SceneResult& r) {
  write_text_atomic(layout.outcome(id).string(), "recorded " + std::to_string(r.recorded_frames) + "\nstored " +
                                                     std::to_string(r.ok ? r.stored_frames : 0) + "\ncut " +
                                                     std::to_string(r.cut_frame) + "\nrule " +
                                                     (r.rule.empty() ? "-" : r.rule) + "\n");
}

Outcome read_outcome(const Layout& layout, const std::string& id) {
  const std::string path = layout.outcome(id).string();
  std::istringstream in(read_text_file(path));
  Outcome o;
  std::string key;
  bool seen[4] = {false, false, false, false};
  while (in >> key) {
    if (key == "recorded" && (in >> o.recorded)) seen[0] = true;
    if (key == "stored" && (in >> o.stored)) seen[1] = true;
    if (key == "cut" && (in >> o.cut)) seen[2] = true;
    if (key == "rule" && (in >> o.rule)) seen[3] = true;
  }
  for (bool b : seen)
    if (!b)
      throw InputError::message(path, "",
                                "a scene outcome of the generator (recorded, stored, cut, rule), damaged; "
                                "delete it and the scene's part to simulate the scene again");
  if (o.rule == "-") o.rule.clear();
  return o;
}

// The motions block of dataset.yaml: distinct motions per family among the
// written sequences, and the scenes of each family that were skipped; with
// clean windows, each family's scenes, cut sequences, recorded frames asked
// for, simulated and stored, and the frames lost by rule.
void count_motions(const Layout& layout, const std::vector<std::string>& motions, data::DatasetManifest& manifest) {
  std::map<std::string, std::set<std::string>> by_family;
  for (const std::string& m : motions) {
    by_family[motion_family(m)].insert(m);
    ++manifest.motion_families[motion_family(m)].sequences;
  }
  std::set<std::string> all(motions.begin(), motions.end());
  manifest.n_distinct_motions = static_cast<std::int64_t>(all.size());
  for (const auto& [family, distinct] : by_family)
    manifest.motion_families[family].distinct = static_cast<std::int64_t>(distinct.size());
  const bool windows = layout.config.window_min_frames > 0;
  for (int i = 0; i < layout.config.sequences; ++i) {
    data::MotionFamilyCount& c = manifest.motion_families[motion_family(sample_scene(layout.config, i).motion)];
    if (fs::exists(layout.skipped(scene_id(i)))) ++c.skipped;
    if (!windows) continue;
    const Outcome o = read_outcome(layout, scene_id(i));
    if (c.scenes < 0) c.scenes = c.cut = c.frames_asked = c.frames_simulated = c.frames_stored = 0;
    ++c.scenes;
    c.frames_asked += layout.config.frames;
    c.frames_simulated += o.recorded;
    c.frames_stored += o.stored;
    if (o.stored > 0 && o.cut >= 0) ++c.cut;
    if (o.stored < layout.config.frames)
      c.dropped[o.rule.empty() ? "unknown" : o.rule] += layout.config.frames - o.stored;
  }
}

// dataset.yaml, splits.yaml and stats.h5, once every shard exists.
FinalizeReport finalize(const Layout& layout, const std::string& config_yaml) {
  FinalizeReport report;
  report.shards = layout.n_shards();
  for (int j = 0; j < layout.n_shards(); ++j)
    if (!fs::exists(layout.shard(j))) report.missing.push_back(j);
  if (!report.missing.empty()) return report;
  // Index every shard once (metadata only): counts, and the split and
  // subsets of every sequence that was written.
  std::map<std::string, std::vector<std::string>> splits;
  std::int64_t sequences = 0, frames = 0, garments = 0;
  std::vector<std::string> motions;
  const std::vector<std::string> split_of = assign_splits(layout.config);
  for (int j = 0; j < layout.n_shards(); ++j) {
    data::Dataset shard = data::Dataset::open(layout.shard(j).string());
    for (const auto& id : shard.ids()) {
      const auto& info = shard.info(id);
      ++sequences;
      frames += info.n_frames;
      garments += static_cast<std::int64_t>(info.garments.size());
      motions.push_back(info.motion);
      if (!is_held_out(info.tags)) splits[split_of.at(std::stoi(id.substr(4)))].push_back(id);
      for (const auto& tag : info.tags) splits[tag].push_back(id);
    }
  }
  data::Splits out;
  for (const char* name : {"train", "val", "test"}) out.set(name, splits[name]);
  for (const char* name : {"T", "T+W", "L", "L+W"}) out.set(name, splits[name]);
  if (!layout.config.splits.unseen_motions.empty()) out.set(kUnseenMotion, splits[kUnseenMotion]);
  if (!layout.config.splits.unseen_outfits.empty()) out.set(kUnseenGarment, splits[kUnseenGarment]);
  data::write_splits((layout.out / "splits.yaml").string(), out);
  data::DatasetManifest manifest;
  manifest.name = layout.config.name;
  manifest.seed = layout.config.seed;
  manifest.sequences_per_shard = layout.config.sequences_per_shard;
  manifest.n_sequences = sequences;
  manifest.n_frames = frames;
  manifest.n_garments = garments;
  manifest.n_shards = layout.n_shards();
  manifest.generator_yaml = config_yaml;
  manifest.generator_revision = source_revision();  // claim_folder checked it against the folder's
  // Only with parametric motions, so datasets made without them keep their bytes.
  if (layout.config.body.variation || layout.config.window_min_frames > 0) count_motions(layout, motions, manifest);
  // Hashes recorded by an earlier finalize are kept, so that they are
  // verified against the shards rather than replaced.
  const fs::path manifest_path = layout.out / "dataset.yaml";
  if (fs::exists(manifest_path)) manifest.content_hashes = data::read_manifest(manifest_path.string()).content_hashes;
  data::write_manifest(manifest_path.string(), manifest);
  data::record_integrity(layout.out.string());
  if (!out.get("train").empty()) {
    data::Dataset ds = data::Dataset::open(layout.out.string());
    data::write_dataset_stats(layout.out.string(), data::compute_stats(ds));
    report.stats = true;
  } else {
    spdlog::warn("{}: no train sequence was written; stats.h5 not computed", layout.out.string());
  }
  std::error_code ec;
  fs::remove(layout.out / "parts", ec);  // only when empty (skipped markers stay)
  report.sequences = sequences;
  report.frames = frames;
  return report;
}

// A refused scene to look at (GenerateOptions::keep_refused). Never
// replaces a file: a name already there is refused.
void write_refused(const std::string& folder, const SceneSpec& spec, const SceneResult& result, double pinch_distance) {
  fs::create_directories(folder);
  const fs::path shard = fs::path(folder) / (spec.id + ".h5");
  const fs::path about = fs::path(folder) / (spec.id + ".refused.yaml");
  if (fs::exists(shard) || fs::exists(about))
    throw InputError(folder, "--keep-refused", "a folder without this scene's files", "'" + shard.string() + "'");
  data::write_shard(shard.string(), {result.sequence});
  // Written with the config tree's emitter (quoting is its job).
  cfg::Node about_node;
  about_node.kind = cfg::Node::Kind::Map;
  const auto scalar = [&](const std::string& key, const std::string& value) {
    cfg::Node& n = about_node.child(key);
    n.kind = cfg::Node::Kind::Scalar;
    n.scalar = value;
  };
  scalar("scene", spec.id);
  scalar("motion", spec.motion);
  scalar("rule", result.rule.empty() ? std::string("none") : result.rule);
  scalar("first_broken_frame", std::to_string(result.cut_frame));
  scalar("frames_kept", std::to_string(result.sequence.wind.strength.size()));
  const auto list = [&](const std::string& key, const std::vector<std::string>& lines) {
    cfg::Node& node = about_node.child(key);
    node.kind = cfg::Node::Kind::Seq;
    for (const std::string& v : lines) {
      cfg::Node item;
      item.kind = cfg::Node::Kind::Scalar;
      item.scalar = v;
      node.seq.push_back(item);
    }
  };
  list("violations", result.violations);
  // Where on the garments: the most stretched edges of the frame that broke
  // the rule (without a clean-window cut, of the most stretched frame).
  const int kept = static_cast<int>(result.sequence.wind.strength.size());
  if (kept > 0) {
    const int at =
        result.cut_frame >= 0 && result.cut_frame < kept ? result.cut_frame : most_stretched_frame(result.sequence);
    scalar("where_frame", std::to_string(at));
    list("most_stretched_edges", most_stretched_edges(result.sequence, at, 5));
    list("crossings", crossing_places(result.sequence, at, pinch_distance, 3));
  }
  const std::string text = cfg::to_yaml(about_node);
  write_text_atomic(about.string(), text);
}

}  // namespace

void check_output_folder(const std::string& out) {
  // A folder no generation started (no generator.yaml) must be new or
  // empty: its files are the user's, and finalizing would replace some.
  const fs::path dir(out);
  std::error_code ec;
  if (fs::exists(dir) && !fs::exists(dir / "generator.yaml") && !(fs::is_directory(dir) && fs::is_empty(dir, ec)))
    throw InputError(out, "--out",
                     "a new or empty folder, or a dataset folder a generation with this config started "
                     "(generator.yaml)",
                     fs::is_directory(dir) ? "a folder holding other files" : "a file");
}

GenerateReport generate_dataset(const GeneratorConfig& config, const std::string& config_yaml,
                                const GenerateOptions& options) {
  Timer wall;
  Layout layout{options.out, config};
  claim_folder(layout, config_yaml);
  GenerateReport report;

  std::vector<int> todo;
  for (int j = options.shard_index; j < layout.n_shards(); j += options.shard_count) {
    for (int i = layout.first(j); i < layout.end(j); ++i) {
      ++report.scenes;
      if (fs::exists(layout.shard(j)) || layout.scene_done(i))
        ++report.reused;
      else
        todo.push_back(i);
    }
    merge_shard(layout, j);  // a shard whose parts were all finished before
  }

  Progress progress("generate " + config.name, todo.size(), "scenes");
  std::mutex mutex;  // report, progress, shard merging
  // Scenes on `threads` threads; a failure stops new scenes and is rethrown.
  parallel_indices(todo.size(), options.threads, [&](std::size_t k) {
    const SceneSpec spec = sample_scene(config, todo[k]);
    SceneResult result = simulate_scene(config, spec, {}, !options.keep_refused.empty());
    std::string reasons;
    for (const auto& v : result.violations) reasons += (reasons.empty() ? "" : "; ") + v;
    if (!result.ok && !options.keep_refused.empty() && !result.sequence.garments.empty())
      write_refused(options.keep_refused, spec, result, config.sim.validation.pinch_distance);
    // The outcome first: a scene counts as done once its part or marker exists.
    if (config.window_min_frames > 0) write_outcome(layout, spec.id, result);
    if (result.ok)
      data::write_shard(layout.part(spec.id).string(), {result.sequence});
    else
      write_text_atomic(layout.skipped(spec.id).string(), reasons + "\n");
    std::lock_guard<std::mutex> lock(mutex);
    ++report.simulated;
    report.simulated_frames += result.simulated_frames;
    report.simulate_seconds += result.seconds;
    report.simulate_cpu_seconds += result.cpu_seconds;
    if (result.ok) {
      ++report.written;
      if (result.cut_frame >= 0) ++report.cut;
    } else {
      ++report.skipped;
      report.skip_reasons.push_back(spec.id + " (" + motion_family(spec.motion) + "): " + reasons);
      spdlog::warn("{} skipped ({}): {}", spec.id, spec.motion, reasons);
    }
    merge_shard(layout, todo[k] / config.sequences_per_shard);
    if (options.progress)
      progress.advance(1, "h-pen " + std::to_string(100.0 * result.mean_h_penetration).substr(0, 4) + "% skipped " +
                              std::to_string(report.skipped));
  });
  if (options.progress && !todo.empty()) progress.finish();

  if (options.finalize) {
    const FinalizeReport fin = finalize(layout, config_yaml);
    report.finalized = fin.done();
    report.stats = fin.stats;
  }
  report.seconds = wall.seconds();
  return report;
}

FinalizeReport finalize_dataset(const GeneratorConfig& config, const std::string& config_yaml, const std::string& out) {
  const Layout layout{out, config};
  if (!check_saved_config(layout, config_yaml))
    throw InputError::message((layout.out / "generator.yaml").string(), "",
                              "not found: no `layers generate` run has started this dataset folder; generate its "
                              "shards first (same --config, --set and --out)");
  check_revision(layout, true);
  // Shards whose scenes are all finished but were not merged (a run
  // stopped in between). Only here: a generate run merges only its own
  // shards, so that two runs never merge the same one at once.
  for (int j = 0; j < layout.n_shards(); ++j) merge_shard(layout, j);
  return finalize(layout, config_yaml);
}

bool dataset_complete(const std::string& folder, const GeneratorConfig& config) {
  const Layout layout{folder, config};
  if (!fs::exists(layout.out / "dataset.yaml") || !fs::exists(layout.out / "splits.yaml")) return false;
  for (int j = 0; j < layout.n_shards(); ++j)
    if (!fs::exists(layout.shard(j))) return false;
  const data::Splits splits = data::read_splits((layout.out / "splits.yaml").string());
  return fs::exists(layout.out / "stats.h5") || !splits.has("train") || splits.get("train").empty();
}

}  // namespace layers::generate
