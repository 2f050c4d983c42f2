// Cross-field checks of the generator config, and reading the one a
// dataset manifest records (see generator_config.h).
#include "layers/generate/generator_config.h"

#include <algorithm>

#include "layers/core/error.h"
#include "layers/core/text_file.h"
#include "layers/data/format.h"
#include "layers/generate/imported_garment.h"
#include "layers/generate/own_body.h"
#include "layers/import/garment_file.h"
#include "layers/motion/motion.h"

namespace layers::generate {
namespace {

template <class T>
void check_pair(const std::vector<T>& range, const std::string& file, const std::string& path) {
  if (range.size() != 2 || range[0] > range[1])
    throw InputError(file, path, "a range [lo, hi] with lo <= hi",
                     std::to_string(range.size()) + " values" + (range.size() == 2 ? " with lo > hi" : ""));
}

bool is_outer(const std::string& type) { return data::garment_type_layer(type) == 1; }

std::string joined(const std::vector<std::string>& names) {
  std::string out;
  for (const auto& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// Every held-out motion and outfit is one the config samples, and at
// least one of each stays seen.
void check_holdouts(const GeneratorConfig& c, const std::string& file) {
  std::vector<std::string> labels;
  for (const auto& o : c.garments.outfits) labels.push_back(outfit_label(o));
  auto check_list = [&](const std::vector<std::string>& held, const std::vector<std::string>& known,
                        const std::string& path) {
    for (std::size_t i = 0; i < held.size(); ++i) {
      if (std::find(known.begin(), known.end(), held[i]) == known.end())
        throw InputError(file, path + "[" + std::to_string(i) + "]", "one of " + joined(known), "'" + held[i] + "'");
    }
    std::size_t kept = 0;
    for (const auto& k : known) kept += std::find(held.begin(), held.end(), k) == held.end();
    if (kept == 0 && !known.empty())
      throw InputError(file, path, "at least one entry left for training", "all of them held out");
  };
  check_list(c.splits.unseen_motions, c.body.motions, "splits.unseen_motions");
  check_list(c.splits.unseen_outfits, labels, "splits.unseen_outfits");
}

}  // namespace

std::string outfit_label(const OutfitConfig& outfit) {
  std::string label;
  for (const auto& t : outfit.inner) label += (label.empty() ? "" : "+") + t;
  return label + "/" + outfit.outer;
}

bool same_saved_config(const std::string& path, const std::string& resolved) {
  if (read_text_file(path) == resolved) return true;
  try {
    return cfg::to_yaml(cfg::to_node(cfg::read<GeneratorConfig>(cfg::load_file(path)))) == resolved;
  } catch (const Error&) {
    return false;
  }
}

void check(const GeneratorConfig& c, const std::string& file) {
  const auto& shape = c.body.shape;
  check_pair(shape.gender, file, "body.shape.gender");
  check_pair(shape.muscle, file, "body.shape.muscle");
  check_pair(shape.weight, file, "body.shape.weight");
  check_pair(shape.height, file, "body.shape.height");
  if (c.body.motions.empty()) throw InputError(file, "body.motions", "at least one motion", "an empty list");
  if (c.body.variation) check(*c.body.variation, file, "body.variation");
  const auto& a = c.garments.attributes;
  check_pair(a.mass, file, "garments.attributes.mass");
  check_pair(a.stiffness, file, "garments.attributes.stiffness");
  check_pair(a.bending, file, "garments.attributes.bending");
  check_pair(a.friction, file, "garments.attributes.friction");
  check_pair(c.wind.calm, file, "wind.calm");
  check_pair(c.wind.strong, file, "wind.strong");
  check_pair(c.wind.mixed, file, "wind.mixed");
  check_pair(c.wind.span_frames, file, "wind.span_frames");
  if (c.wind.calm_weight + c.wind.strong_weight + c.wind.mixed_weight <= 0)
    throw InputError(file, "wind", "at least one positive regime weight", "all zero");
  if (c.window_min_frames != 0 && (c.window_min_frames < 3 || c.window_min_frames > c.frames))
    throw InputError(file, "window_min_frames",
                     "0 (off) or 3 to frames (" + std::to_string(c.frames) + "; a sequence needs 3 frames)",
                     std::to_string(c.window_min_frames));
  if (c.splits.val + c.splits.test >= 1.0)
    throw InputError(file, "splits", "val + test < 1 (the rest is train)",
                     std::to_string(c.splits.val + c.splits.test));
  double total = 0;
  std::string inner_types;
  for (const std::string& t : data::garment_types_of_layer(0)) inner_types += (inner_types.empty() ? "" : ", ") + t;
  for (std::size_t i = 0; i < c.garments.outfits.size(); ++i) {
    const auto& o = c.garments.outfits[i];
    const std::string path = "garments.outfits[" + std::to_string(i) + "]";
    total += o.weight;
    if (o.inner.empty()) throw InputError(file, path + ".inner", "at least one inner garment type", "an empty list");
    std::size_t files = 0;
    for (const auto& t : o.inner) {
      if (import::is_garment_file(t)) {
        import::read_garment_file(t);  // the mesh exists, its side file reads
        ++files;
        continue;
      }
      if (data::garment_type_layer(t) != 0 || !data::is_garment_type(t))
        throw InputError(file, path + ".inner", "inner garment types (" + inner_types + ") or file:<mesh>",
                         "'" + t + "'");
    }
    if (import::is_garment_file(o.outer)) {
      import::read_garment_file(o.outer);
      ++files;
    } else if (o.outer != "none" && !is_outer(o.outer)) {
      std::string outer_types;
      for (const std::string& t : data::garment_types_of_layer(1)) outer_types += t + ", ";
      throw InputError(file, path + ".outer", "an outer garment type (" + outer_types + "none or file:<mesh>)",
                       "'" + o.outer + "'");
    }
    const std::size_t garments = o.inner.size() + (o.outer == "none" ? 0 : 1);
    if (files > 0 && files < garments)
      throw InputError(file, path, "an outfit of templates only or of garment files only",
                       std::to_string(files) + " files among " + std::to_string(garments) + " garments");
  }
  if (total <= 0 && !c.garments.outfits.empty())
    throw InputError(file, "garments.outfits", "at least one outfit with a positive weight", "all zero");
  check_holdouts(c, file);
  check_own_body(c, file);
  garment::validate(c.garments.fit);
  sim::check(c.sim, "sim");
}

void expand_motion_folders(GeneratorConfig& config, const std::string& file) {
  if (config.body.own) return;  // an own body's entries are its animation or clips (own_body.h)
  std::vector<std::string> expanded;
  for (std::size_t i = 0; i < config.body.motions.size(); ++i) {
    const std::string& m = config.body.motions[i];
    std::vector<std::string> clips =
        m.rfind("procedural:", 0) == 0
            ? std::vector<std::string>{}
            : motion::clip_folder_entries(m, file + ": body.motions[" + std::to_string(i) + "]");
    if (clips.empty())
      expanded.push_back(m);
    else
      expanded.insert(expanded.end(), clips.begin(), clips.end());
  }
  config.body.motions = std::move(expanded);
}

GeneratorConfig load_generator_config(const std::string& file, const std::vector<std::string>& sets, bool to_simulate) {
  cfg::Node tree = cfg::load_file(file);
  for (const std::string& s : sets) cfg::apply_set(tree, s);
  GeneratorConfig config = cfg::read<GeneratorConfig>(tree);
  expand_motion_folders(config, file);
  check(config, file);
  if (to_simulate && config.garments.outfits.empty())
    throw InputError(file, "garments.outfits",
                     "at least one outfit to simulate (an empty list is for `layers tpose`, which writes the body "
                     "alone)",
                     "an empty list");
  resolve_garment_files(config);
  resolve_own_body(config);
  return config;
}

std::optional<GeneratorConfig> recorded_generator_config(const std::string& generator_yaml, const std::string& file) {
  if (generator_yaml.empty()) return std::nullopt;
  return cfg::read<GeneratorConfig>(cfg::parse(generator_yaml, file), "generator");
}

}  // namespace layers::generate
