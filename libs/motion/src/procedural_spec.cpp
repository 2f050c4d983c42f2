// The text side of procedural motions (see procedural.h): the variants of
// each kind, the seeded default draw, and the replayable description
// "procedural:<kind> key=value ..." with its parser.
#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <sstream>

#include "layers/core/error.h"
#include "layers/motion/procedural.h"

namespace layers::motion {
namespace {

bool uses_step(const std::string& kind) {
  return kind == "walk" || kind == "run" || kind == "jump" || kind == "hop" || kind == "step_down";
}
bool uses_turn(const std::string& kind) { return kind == "turn" || kind == "spin"; }

std::string fixed(double value, int decimals) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  return buf;
}

}  // namespace

const std::vector<std::string>& procedural_variants(const std::string& kind) {
  static const std::map<std::string, std::vector<std::string>> variants = {
      {"arm_raise",
       {"front-both", "front-left", "front-right", "front-alternate", "side-both", "side-left", "side-right",
        "side-alternate"}},
      {"wave", {"left", "right"}},
      {"step_down", {"left", "right"}},  // the leading foot
      {"jump", {"in_place", "forward"}},
      {"hop", {"in_place", "forward"}}};
  static const std::vector<std::string> none;
  const auto it = variants.find(kind);
  return it == variants.end() ? none : it->second;
}

ProceduralParams sample_procedural(const std::string& kind, int frames, std::uint64_t seed) {
  ProceduralParams p;
  p.kind = kind;
  p.frames = frames;
  p.seed = seed;
  std::mt19937_64 gen(seed * 0x2545F4914F6CDD1Dull + 17);
  p.speed = std::uniform_real_distribution<double>(0.8, 1.25)(gen);
  p.amplitude = std::uniform_real_distribution<double>(0.75, 1.25)(gen);
  return p;
}

std::string describe_procedural(const ProceduralParams& p) {
  std::string out = "procedural:" + p.kind;
  if (!p.explicit_params) return out;
  out += " speed=" + fixed(p.speed, 3) + " amplitude=" + fixed(p.amplitude, 3) + " phase=" + fixed(p.phase, 3);
  if (uses_step(p.kind)) out += " step=" + fixed(p.step_length, 3);
  if (uses_turn(p.kind)) {
    if (p.turn_angle > 0) out += " turn=" + fixed(p.turn_angle, 1);
    if (p.direction != 0) out += std::string(" dir=") + (p.direction > 0 ? "left" : "right");
  }
  const auto& variants = procedural_variants(p.kind);
  if (p.variant >= 0 && !variants.empty())
    out += " variant=" + variants[static_cast<std::size_t>(p.variant) % variants.size()];
  char seed[32];
  std::snprintf(seed, sizeof seed, "%016llx", static_cast<unsigned long long>(p.seed));
  return out + " seed=" + seed;
}

ProceduralParams parse_procedural(const std::string& text, int frames, std::uint64_t seed, const std::string& field) {
  std::istringstream in(text);
  std::string kind, token;
  in >> kind;
  ProceduralParams p = sample_procedural(kind, frames, seed);
  const std::string where = "procedural:" + kind;
  while (in >> token) {
    const auto eq = token.find('=');
    const std::string key = token.substr(0, eq), value = eq == std::string::npos ? "" : token.substr(eq + 1);
    auto number = [&]() {
      std::size_t used = 0;
      double v = 0.0;
      try {
        v = std::stod(value, &used);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != value.size() || !std::isfinite(v))
        throw InputError(field, where + " " + key, "a number", "'" + value + "'");
      return v;
    };
    p.explicit_params = true;
    if (key == "speed") {
      p.speed = number();
    } else if (key == "amplitude") {
      p.amplitude = number();
    } else if (key == "phase") {
      p.phase = number();
    } else if (key == "step") {
      p.step_length = number();
    } else if (key == "turn") {
      p.turn_angle = number();
    } else if (key == "dir") {
      if (value != "left" && value != "right")
        throw InputError(field, where + " dir", "left or right", "'" + value + "'");
      p.direction = value == "left" ? 1 : -1;
    } else if (key == "variant") {
      const auto& variants = procedural_variants(kind);
      p.variant = -1;
      for (std::size_t i = 0; i < variants.size(); ++i)
        if (variants[i] == value) p.variant = static_cast<int>(i);
      if (p.variant < 0) {
        std::string list;
        for (const auto& v : variants) list += (list.empty() ? "" : ", ") + v;
        throw InputError(field, where + " variant", list.empty() ? "no variant (the kind has none)" : "one of " + list,
                         "'" + value + "'");
      }
    } else if (key == "seed") {
      std::size_t used = 0;
      try {
        p.seed = std::stoull(value, &used, 16);
      } catch (const std::exception&) {
        used = 0;
      }
      if (used == 0 || used != value.size()) throw InputError(field, where + " seed", "hex digits", "'" + value + "'");
    } else {
      throw InputError(field, where, "key=value with a key of speed, amplitude, phase, step, turn, dir, variant, seed",
                       "'" + token + "'");
    }
  }
  return p;
}

}  // namespace layers::motion
