// Deterministic sampling of scenes (see scene_spec.h).
#include "layers/generate/scene_spec.h"

#include "layers/import/garment_file.h"

#include "layers/data/format.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

#include "layers/generate/random.h"

namespace layers::generate {
namespace {

sim::GarmentAttributes sample_attributes(const AttributeRanges& r, Rng& rng) {
  sim::GarmentAttributes a;
  a.mass = rng.uniform(r.mass);
  a.tension = rng.uniform(r.stiffness);
  a.compression = rng.uniform(r.stiffness);
  a.shear = rng.uniform(r.stiffness);
  a.bending = rng.uniform(r.bending);
  a.friction = rng.uniform(r.friction);
  a.self_friction = rng.uniform(r.friction);
  return a;
}

std::vector<sim::WindSpan> sample_wind(const WindConfig& w, int frames, const std::vector<double>& strength, Rng& rng) {
  std::vector<sim::WindSpan> spans;
  const double max_elevation = w.max_elevation_deg * M_PI / 180.0;
  for (int begin = 0; begin < frames;) {
    int end = std::min(frames, begin + rng.integer(w.span_frames.at(0), w.span_frames.at(1)));
    double azimuth = rng.uniform(0.0, 2.0 * M_PI);
    double elevation = rng.uniform(-max_elevation, max_elevation);
    sim::WindSpan span;
    span.begin = begin;
    span.end = end;
    span.wind.direction = sim::Vec3(std::cos(elevation) * std::sin(azimuth), std::sin(elevation),
                                    std::cos(elevation) * std::cos(azimuth));
    span.wind.strength = rng.uniform(strength);
    spans.push_back(span);
    begin = end;
  }
  return spans;
}

// A scene's first draws: its body shape and its body.motions entry.
std::string draw_body(const GeneratorConfig& config, Rng& rng, body::ShapeParams& out) {
  const auto& shape = config.body.shape;
  out.gender = rng.uniform(shape.gender);
  out.muscle = rng.uniform(shape.muscle);
  out.weight = rng.uniform(shape.weight);
  out.height = rng.uniform(shape.height);
  return config.body.motions.at(rng.integer(0, static_cast<int>(config.body.motions.size()) - 1));
}

}  // namespace

std::string scene_id(int index) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "seq-%06d", index);
  return buf;
}

std::vector<std::string> subset_tags(const std::vector<GarmentSpec>& garments, const std::vector<sim::WindSpan>& wind) {
  std::vector<std::string> inner;
  bool jacket = false;
  for (const auto& g : garments) {
    if (g.layer == 0) inner.push_back(g.type);
    if (g.layer == 1 && data::garment_type_layer(g.type) == 1) jacket = true;
  }
  if (!jacket || inner.size() != 1 || wind.empty()) return {};
  const data::GarmentTypeInfo* type = data::find_garment_type(inner[0]);
  const std::string base = type ? type->subset : "";
  if (base.empty()) return {};
  bool calm = true, strong = true;
  for (const auto& span : wind) {
    calm = calm && span.wind.strength <= 50.0;
    strong = strong && span.wind.strength > 250.0;
  }
  if (calm) return {base};
  if (strong) return {base + "+W"};
  return {};
}

bool is_held_out(const std::vector<std::string>& tags) {
  for (const std::string& t : tags)
    if (t == kUnseenMotion || t == kUnseenGarment) return true;
  return false;
}

std::vector<std::string> assign_splits(const GeneratorConfig& config) {
  const int n = config.sequences;
  std::vector<int> order(n);
  std::iota(order.begin(), order.end(), 0);
  Rng rng(derive_seed(config.seed, 0x5917u));
  for (int i = n - 1; i > 0; --i) std::swap(order[i], order[rng.integer(0, i)]);
  const int n_test = static_cast<int>(std::lround(config.splits.test * n));
  const int n_val = static_cast<int>(std::lround(config.splits.val * n));
  std::vector<std::string> split(n, "train");
  for (int k = 0; k < n; ++k) {
    if (k < n_test)
      split[order[k]] = "test";
    else if (k < n_test + n_val)
      split[order[k]] = "val";
  }
  return split;
}

SceneSpec sample_scene(const GeneratorConfig& config, int index) {
  SceneSpec s;
  s.index = index;
  s.id = scene_id(index);
  s.seed = derive_seed(config.seed, static_cast<std::uint64_t>(index) + 1);
  Rng rng(s.seed);
  s.motion_entry = draw_body(config, rng, s.shape);
  s.motion = s.motion_entry;
  if (config.body.variation) {
    int occurrence = 0;  // earlier scenes playing the same entry (clip windows are drawn without replacement)
    if (s.motion_entry.rfind("procedural:", 0) != 0) {
      for (int j = 0; j < index; ++j) {
        Rng other(derive_seed(config.seed, static_cast<std::uint64_t>(j) + 1));
        body::ShapeParams unused;
        occurrence += draw_body(config, other, unused) == s.motion_entry;
      }
    }
    s.motion = vary_motion(*config.body.variation, s.motion_entry, config.frames, s.seed, occurrence, config.seed);
  }

  // No outfit (a config for the body alone, `layers tpose`): no garments.
  std::vector<double> weights;
  for (const auto& o : config.garments.outfits) weights.push_back(o.weight);
  const OutfitConfig outfit =
      config.garments.outfits.empty() ? OutfitConfig{{}, "none"} : config.garments.outfits.at(rng.pick(weights));
  const auto garment = [&](const std::string& entry, int layer) {
    const bool file = import::is_garment_file(entry);
    return GarmentSpec{file ? "imported" : entry, layer, sample_attributes(config.garments.attributes, rng),
                       file ? entry : ""};
  };
  for (const auto& entry : outfit.inner) s.garments.push_back(garment(entry, 0));
  if (outfit.outer != "none") s.garments.push_back(garment(outfit.outer, 1));

  const WindConfig& w = config.wind;
  std::size_t regime = rng.pick({w.calm_weight, w.strong_weight, w.mixed_weight});
  static const char* names[] = {"calm", "strong", "mixed"};
  s.wind_regime = names[regime];
  const std::vector<double>& strength = regime == 0 ? w.calm : regime == 1 ? w.strong : w.mixed;
  s.wind = sample_wind(w, config.frames, strength, rng);

  s.split = assign_splits(config).at(index);
  s.tags = subset_tags(s.garments, s.wind);
  auto held = [](const std::vector<std::string>& list, const std::string& name) {
    return std::find(list.begin(), list.end(), name) != list.end();
  };
  if (held(config.splits.unseen_motions, s.motion_entry)) s.tags.push_back(kUnseenMotion);
  if (held(config.splits.unseen_outfits, outfit_label(outfit))) s.tags.push_back(kUnseenGarment);
  if (is_held_out(s.tags)) s.split.clear();
  return s;
}

}  // namespace layers::generate
