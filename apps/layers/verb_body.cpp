// `layers body`: a shaped MPFB2 body moved by a BVH clip or a procedural
// motion, written as the body part of a LAYERS-H5 sequence (a shard file
// or a dataset folder), optionally exported to OBJ/PC2 for a look.
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "layers/core/error.h"
#include "layers/core/progress.h"
#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/export.h"
#include "layers/data/shard_writer.h"
#include "layers/generate/body_data.h"
#include "layers/motion/body_config.h"
#include "output_folder.h"
#include "verbs.h"

namespace fs = std::filesystem;

namespace layers::app {
namespace {

cfg::Node scalar(const std::string& value, const std::string& flag) {
  cfg::Node n;
  n.kind = cfg::Node::Kind::Scalar;
  n.scalar = value;
  n.file = flag;
  return n;
}

// "gender=0.3,height=0.7" -> a shape mapping (checked by the typed reader).
cfg::Node parse_shape(const std::string& text) {
  cfg::Node shape;
  shape.kind = cfg::Node::Kind::Map;
  shape.file = "--shape";
  std::size_t begin = 0;
  while (begin <= text.size()) {
    std::size_t comma = text.find(',', begin);
    std::string item = text.substr(begin, comma == std::string::npos ? std::string::npos : comma - begin);
    auto eq = item.find('=');
    if (eq == std::string::npos || eq == 0)
      throw InputError("--shape", "'" + item + "'",
                       "name=value pairs separated by commas (gender, muscle, weight, height)", "'" + text + "'");
    shape.map.emplace_back(item.substr(0, eq), scalar(item.substr(eq + 1), "--shape"));
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return shape;
}

}  // namespace

VerbRun register_body(CLI::App& app, const Global&) {
  auto* cmd = app.add_subcommand("body", "Generate a moving body (MPFB2 + BVH or procedural motion) as LAYERS-H5");
  struct Args {
    std::string shape, motion = "procedural:walk", out, id = "body-0000", export_format, export_dir;
    std::string on_intersection = "longest_run";
    int frames = 120, transition = 15;
    std::uint64_t seed = 0;
    double arm_room = 0.0, thigh_room = 0.0, gap = 0.0;
    int skin_untangle = 0;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--shape", a->shape, "shape parameters in 0..1, e.g. gender=0.3,muscle=0.5,weight=0.6,height=0.45");
  cmd->add_option("--motion", a->motion, "procedural:<kind>, bvh:<path> or a .bvh file")->capture_default_str();
  cmd->add_option("--frames", a->frames, "frames at 30 fps, transition included; 0 = whole clip")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--transition", a->transition, "frames blending in from the T-pose")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--seed", a->seed, "randomises procedural speed and amplitude")->capture_default_str();
  cmd->add_option("--on-intersection", a->on_intersection, "longest_run, first_run, drop or keep")
      ->capture_default_str();
  cmd->add_option("--gap", a->gap,
                  "mm of room body parts that are not neighbours keep from each other (0 = off: depth over 4 mm "
                  "counts; the paper keeps 4)")
      ->capture_default_str();
  cmd->add_option("--arm-room", a->arm_room, "mm of room for the cloth between arms and torso (0 = off)")
      ->capture_default_str();
  cmd->add_option("--thigh-room", a->thigh_room, "mm of room for the cloth between the legs, thighs to feet (0 = off)")
      ->capture_default_str();
  cmd->add_option("--skin-untangle", a->skin_untangle,
                  "rounds of pushing the posed skin out of itself where it crosses itself (0 = off)")
      ->capture_default_str();
  cmd->add_option("--id", a->id, "sequence id")->capture_default_str();
  cmd->add_option("--out", a->out, "output: a shard file (*.h5) or a dataset folder")->required();
  cmd->add_option("--export", a->export_format, "also export the body as obj or pc2");
  cmd->add_option("--export-dir", a->export_dir, "folder for --export (default <out>_export)");
  return [a]() {
    // The flags checked in their own names (the motion's checks name config keys).
    if (a->frames < 0)
      throw UsageError("--frames: expected 0 (the whole clip) or more, got " + std::to_string(a->frames));
    if (a->transition < 0) throw UsageError("--transition: expected 0 or more, got " + std::to_string(a->transition));
    if (a->frames > 0 && a->transition >= a->frames)
      throw UsageError("--transition: expected fewer frames than --frames (" + std::to_string(a->frames) + "), got " +
                       std::to_string(a->transition));
    claim_new_output(a->out, "--out");
    cfg::Node section;
    section.kind = cfg::Node::Kind::Map;
    section.file = "layers body";
    if (!a->shape.empty()) section.map.emplace_back("shape", parse_shape(a->shape));
    section.map.emplace_back("motion", scalar(a->motion, "--motion"));
    section.map.emplace_back("frames", scalar(std::to_string(a->frames), "--frames"));
    section.map.emplace_back("transition_frames", scalar(std::to_string(a->transition), "--transition"));
    section.map.emplace_back("seed", scalar(std::to_string(a->seed), "--seed"));
    section.map.emplace_back("on_intersection", scalar(a->on_intersection, "--on-intersection"));
    section.map.emplace_back("self_gap_mm", scalar(std::to_string(a->gap), "--gap"));
    section.map.emplace_back("arm_room_mm", scalar(std::to_string(a->arm_room), "--arm-room"));
    section.map.emplace_back("thigh_room_mm", scalar(std::to_string(a->thigh_room), "--thigh-room"));
    cfg::Node untangle;
    untangle.kind = cfg::Node::Kind::Map;
    untangle.file = section.file;
    untangle.map.emplace_back("passes", scalar(std::to_string(a->skin_untangle), "--skin-untangle"));
    section.map.emplace_back("skin_untangle", untangle);
    auto config = cfg::read<motion::BodyMotionConfig>(section, "body");
    if (!a->export_format.empty()) data::parse_export_format(a->export_format, "--export");

    Timer timer;
    motion::GeneratedBody generated = motion::generate_body(config);
    double seconds = timer.seconds();
    data::SequenceData seq = generate::body_only_sequence(generated, a->id, config.seed);

    const bool shard = fs::path(a->out).extension() == ".h5";
    if (shard) {
      if (fs::path(a->out).has_parent_path()) fs::create_directories(fs::path(a->out).parent_path());
      data::write_shard(a->out, {seq});
    } else {
      data::DatasetWriterOptions options;
      options.name = "body";
      options.seed = config.seed;
      data::DatasetWriter writer(a->out, options);
      writer.add(seq);
      writer.set_split("train", {seq.id});
      writer.finish();
    }
    const auto& report = generated.sequence.intersection;
    std::printf("%s: %lld frames of %s, %d body vertices, %d joints, stature %.3f m\n", a->out.c_str(),
                static_cast<long long>(seq.n_frames), seq.motion.c_str(), generated.sequence.num_vertices,
                generated.sequence.num_joints, generated.body.stature());
    std::printf("generation: %.2f s (%.1f frames/s)\n", seconds, seconds > 0 ? seq.n_frames / seconds : 0.0);
    char rule[96];
    if (config.self_gap_mm > 0)
      std::snprintf(rule, sizeof rule, "closer than %.1f mm (or deeper than %.1f mm by the joints)", config.self_gap_mm,
                    config.intersection_tolerance_mm);
    else
      std::snprintf(rule, sizeof rule, "deeper than %.1f mm", config.intersection_tolerance_mm);
    std::printf(
        "self-intersection: %d of %d frames (%.1f%%) %s before repair, deepest %.1f mm; "
        "%d resolved, %d unresolvable (deepest %.1f mm), %d dropped\n",
        report.intersecting, report.frames, 100.0 * report.share_intersecting(), rule, 1000.0 * report.worst_before,
        report.resolved, report.remaining, 1000.0 * report.worst_after, report.dropped);
    std::printf("repair: limbs turned in %d of %d frames, by up to %.1f degrees, skin moved by up to %.1f mm\n",
                report.corrected, report.frames, report.max_turn * 180.0 / M_PI, 1000.0 * report.max_shift);
    std::printf(
        "exact crossings between body regions: %.1f face pairs per frame before repair, %.1f after (the repair "
        "aimed at those of %d of 4 limbs)\n",
        report.frames ? static_cast<double>(report.crossing_before) / report.frames : 0.0,
        report.frames ? static_cast<double>(report.crossing_after) / report.frames : 0.0, report.crossing_limbs);
    if (config.arm_room_mm > 0)
      std::printf("arm room %.0f mm: %s\n", config.arm_room_mm,
                  report.arm_room.describe("arms", report.frames).c_str());
    if (config.thigh_room_mm > 0)
      std::printf("thigh room %.0f mm: %s\n", config.thigh_room_mm,
                  report.thigh_room.describe("legs", report.frames).c_str());
    if (config.skin_untangle.passes > 0)
      std::printf(
          "skin untangling: %d of %d frames changed; skin faces crossing the skin: %.1f per frame before, "
          "%.1f after\n",
          report.skin_frames, static_cast<int>(seq.n_frames),
          seq.n_frames ? static_cast<double>(report.skin_crossing_before) / seq.n_frames : 0.0,
          seq.n_frames ? static_cast<double>(report.skin_crossing_after) / seq.n_frames : 0.0);

    if (!a->export_format.empty()) {
      std::string dir =
          a->export_dir.empty() ? (fs::path(a->out).replace_extension("").string() + "_export") : a->export_dir;
      data::Dataset ds = data::Dataset::open(a->out);
      auto files =
          data::export_sequence(ds, seq.id, data::parse_export_format(a->export_format, "--export"), 0, -1, dir);
      std::printf("exported %zu files to %s\n", files.size(), dir.c_str());
    }
    return static_cast<int>(kOk);
  };
}

}  // namespace layers::app
