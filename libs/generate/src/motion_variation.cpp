// Per-scene draws of parametric motions (see motion_variation.h).
#include "layers/generate/motion_variation.h"

#include <cmath>
#include <map>
#include <mutex>

#include "layers/core/error.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/random.h"
#include "layers/motion/clip_ops.h"
#include "layers/motion/procedural.h"

namespace layers::generate {
namespace {

std::string draw_procedural(const MotionVariation& v, const std::string& kind, int frames, std::uint64_t seed,
                            Rng& rng) {
  motion::ProceduralParams p;
  p.kind = kind;
  p.frames = frames;
  p.seed = seed;
  p.explicit_params = true;
  // Rounded to what the description prints, so the description replays it.
  p.speed = std::round(rng.uniform(v.speed) * 1000.0) / 1000.0;
  p.amplitude = std::round(rng.uniform(v.amplitude) * 1000.0) / 1000.0;
  p.phase = std::round(rng.uniform(v.phase) * 1000.0) / 1000.0;
  const double step = std::round(rng.uniform(v.step_length) * 1000.0) / 1000.0;
  if (kind == "walk" || kind == "run" || kind == "jump" || kind == "hop" || kind == "step_down") p.step_length = step;
  const double turn = std::round(rng.uniform(v.turn_angle) * 10.0) / 10.0;
  const double spin = std::round(rng.uniform(v.spin_rate) * 10.0) / 10.0;
  const int direction = rng.uniform() < 0.5 ? 1 : -1;
  if (kind == "turn" || kind == "spin") {
    p.turn_angle = kind == "turn" ? turn : spin;
    p.direction = direction;
  }
  const auto& variants = motion::procedural_variants(kind);
  const int variant = rng.integer(0, std::max(1, static_cast<int>(variants.size())) - 1);
  if (!variants.empty()) p.variant = variant;
  return motion::describe_procedural(p);
}

// Clip lengths at 30 fps, read once per path.
int clip_frames(const std::string& path, const std::string& asset_root) {
  static std::mutex mutex;
  static std::map<std::pair<std::string, std::string>, int> known;
  std::lock_guard<std::mutex> lock(mutex);
  const auto key = std::make_pair(path, asset_root);
  auto it = known.find(key);
  if (it == known.end()) it = known.emplace(key, motion::bvh_clip_frames(path, asset_root)).first;
  return it->second;
}

// FNV-1a: a name's stream, the same with any standard library.
std::uint64_t fnv1a(const std::string& text) {
  std::uint64_t h = 0xcbf29ce484222325ull;
  for (unsigned char c : text) h = (h ^ c) * 0x100000001b3ull;
  return h;
}

void check_range(const std::vector<double>& range, const std::string& file, const std::string& path) {
  if (range.size() != 2 || range[0] > range[1])
    throw InputError(file, path, "a range [lo, hi] with lo <= hi",
                     std::to_string(range.size()) + " values" + (range.size() == 2 ? " with lo > hi" : ""));
}

}  // namespace

void check(const MotionVariation& v, const std::string& file, const std::string& path) {
  check_range(v.speed, file, path + ".speed");
  check_range(v.amplitude, file, path + ".amplitude");
  check_range(v.phase, file, path + ".phase");
  check_range(v.step_length, file, path + ".step_length");
  check_range(v.turn_angle, file, path + ".turn_angle");
  check_range(v.spin_rate, file, path + ".spin_rate");
}

std::string vary_motion(const MotionVariation& v, const std::string& entry, int frames, std::uint64_t seed,
                        int occurrence, std::uint64_t dataset_seed, const std::string& asset_root) {
  if (entry.find('=') != std::string::npos) return entry;  // pinned by the config
  if (entry.rfind("procedural:", 0) == 0) {
    // Its own stream, so the rest of the scene draws the same with or without variation.
    Rng rng(derive_seed(seed, 0x766172ull));
    return draw_procedural(v, entry.substr(11), frames, seed, rng);
  }
  const std::string path = entry.rfind("bvh:", 0) == 0 ? entry.substr(4) : entry;
  const int length = clip_frames(path, asset_root);
  if (length < frames)
    throw InputError(entry, "frames", "at most " + std::to_string(length) + " frames (the clip at 30 fps)",
                     std::to_string(frames));
  // This clip's draws: one mirror flag per occurrence, and the windows of
  // the mirrored and the plain occurrences taken in the order of their own
  // permutations.
  const std::uint64_t stream = derive_seed(dataset_seed, fnv1a(path));
  auto mirrored = [&](int k) {
    return Rng(derive_seed(stream, 2 * static_cast<std::uint64_t>(k) + 1)).uniform() < v.mirror;
  };
  const bool mirror = mirrored(occurrence);
  int same = 0;  // earlier occurrences with the same flag
  for (int k = 0; k < occurrence; ++k) same += mirrored(k) == mirror;
  int start = 0;
  if (v.clip_window == "random") {
    std::vector<int> starts(static_cast<std::size_t>(length - frames + 1));
    for (std::size_t i = 0; i < starts.size(); ++i) starts[i] = static_cast<int>(i);
    Rng rng(derive_seed(stream, mirror ? 0xB0ull : 0xA0ull));
    for (int i = static_cast<int>(starts.size()) - 1; i > 0; --i) std::swap(starts[i], starts[rng.integer(0, i)]);
    start = starts[static_cast<std::size_t>(same) % starts.size()];
  }
  return entry + " window=" + std::to_string(start) + "+" + std::to_string(frames) + " mirror=" + (mirror ? "1" : "0");
}

std::string motion_family(const std::string& motion) {
  std::string family = motion.substr(0, motion.find(' '));
  const bool own = family == kOwnAnimation || family.rfind(std::string(kOwnAnimation) + ":", 0) == 0;
  if (family.rfind("procedural:", 0) != 0 && family.rfind("bvh:", 0) != 0 && !own) family = "bvh:" + family;
  return family;
}

}  // namespace layers::generate
