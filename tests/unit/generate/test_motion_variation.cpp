// Parametric motions in the generator (body.variation): drawn parameters
// stay in their ranges and differ per scene, clip windows fit their clips,
// every scene of a draw plays its own motion, configs without the section
// draw as before, and bad values are refused in one line.
#include <gtest/gtest.h>

#include <map>
#include <set>
#include <sstream>
#include <string>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/motion_variation.h"
#include "layers/generate/scene_spec.h"
#include "layers/motion/clip_ops.h"
#include "layers/motion/procedural.h"
#include "test_paths.h"

namespace layers {
namespace {

generate::GeneratorConfig load(const std::string& name) {
  return cfg::read<generate::GeneratorConfig>(cfg::load_file(test::source_dir() + "/configs/data/" + name), name);
}

// key=value tokens of a description.
std::map<std::string, std::string> tokens(const std::string& text) {
  std::map<std::string, std::string> out;
  std::istringstream in(text);
  std::string word;
  in >> word;
  while (in >> word) out[word.substr(0, word.find('='))] = word.substr(word.find('=') + 1);
  return out;
}

bool within(double x, const std::vector<double>& range) { return x >= range[0] - 1e-9 && x <= range[1] + 1e-9; }

TEST(MotionVariation, DrawsStayInTheirRangesAndDifferPerSeed) {
  generate::MotionVariation v;
  v.speed = {1.2, 1.75};
  v.turn_angle = {150, 270};
  v.spin_rate = {200, 360};
  for (const std::string& kind : motion::procedural_kinds()) {
    std::set<std::string> seen;
    for (std::uint64_t seed = 0; seed < 40; ++seed) {
      const std::string m = generate::vary_motion(v, "procedural:" + kind, 60, seed);
      seen.insert(m);
      // The description is what make_motion reads back.
      const motion::ProceduralParams p = motion::parse_procedural(m.substr(11), 60, 0, "test");
      EXPECT_EQ(motion::describe_procedural(p), m);
      EXPECT_EQ(p.seed, seed);
      EXPECT_TRUE(within(p.speed, v.speed)) << m;
      EXPECT_TRUE(within(p.amplitude, v.amplitude)) << m;
      EXPECT_TRUE(within(p.phase, v.phase)) << m;
      const auto t = tokens(m);
      if (t.count("step")) {
        EXPECT_TRUE(within(p.step_length, v.step_length)) << m;
      }
      if (kind == "turn") {
        EXPECT_TRUE(within(p.turn_angle, v.turn_angle)) << m;
      }
      if (kind == "spin") {
        EXPECT_TRUE(within(p.turn_angle, v.spin_rate)) << m;
      }
      EXPECT_EQ(t.count("dir") == 1, kind == "turn" || kind == "spin") << m;
      EXPECT_EQ(t.count("variant") == 1, !motion::procedural_variants(kind).empty()) << m;
    }
    EXPECT_EQ(seen.size(), 40u) << kind;
  }
}

// Windows are drawn without replacement, so a clip's scenes never repeat one.
TEST(MotionVariation, ClipWindowsFitDifferAndMirrorAboutHalf) {
  generate::MotionVariation v;
  v.clip_window = "random";
  v.mirror = 0.5;
  const std::string clip = "cmu/131_02_start_walk_stop.bvh";
  const int n = motion::bvh_clip_frames(clip);
  int mirrored = 0, later = 0;
  std::set<std::string> seen;
  for (int k = 0; k < 100; ++k) {  // the clip's first 100 scenes in a dataset
    const std::string m = generate::vary_motion(v, clip, 90, 0, k, 7);
    EXPECT_TRUE(seen.insert(m).second) << "drawn twice: " << m;
    const auto t = tokens(m);
    const int start = std::stoi(t.at("window").substr(0, t.at("window").find('+')));
    EXPECT_EQ(t.at("window").substr(t.at("window").find('+') + 1), "90");
    EXPECT_GE(start, 0);
    EXPECT_LE(start + 90, n) << m;
    mirrored += t.at("mirror") == "1";
    later += start > 0;
  }
  EXPECT_GT(mirrored, 30);
  EXPECT_LT(mirrored, 70);
  EXPECT_GT(later, 90);
  v.clip_window = "start";
  v.mirror = 0.0;
  EXPECT_EQ(generate::vary_motion(v, clip, 90, 3), clip + " window=0+90 mirror=0");
  EXPECT_THROW(generate::vary_motion(v, clip, n + 1, 3), InputError);
}

TEST(MotionVariation, EveryScenePlaysItsOwnMotion) {
  // As the generator loads it (the library folder stands for its clips).
  generate::GeneratorConfig config =
      generate::load_generator_config(test::source_dir() + "/configs/data/medium.yaml", {}, false);
  config.sequences = 50;
  generate::check(config, "medium.yaml");
  std::set<std::string> motions, families;
  for (int i = 0; i < config.sequences; ++i) {
    const generate::SceneSpec s = generate::sample_scene(config, i);
    EXPECT_TRUE(motions.insert(s.motion).second) << "two scenes play " << s.motion;
    EXPECT_EQ(generate::motion_family(s.motion), generate::motion_family(s.motion_entry));
    families.insert(generate::motion_family(s.motion));
  }
  EXPECT_GE(families.size(), 10u);
  EXPECT_EQ(generate::motion_family("cmu/a.bvh window=0+9 mirror=1"), "bvh:cmu/a.bvh");
}

TEST(MotionVariation, WithoutTheSectionScenesDrawAsBefore) {
  const generate::GeneratorConfig plain = load("small_tables.yaml");
  EXPECT_FALSE(plain.body.variation.has_value());
  EXPECT_EQ(cfg::to_yaml(cfg::to_node(plain)).find("variation"), std::string::npos);
  generate::GeneratorConfig varied = plain;
  varied.body.variation = generate::MotionVariation{};
  for (int i = 0; i < 20; ++i) {
    const generate::SceneSpec a = generate::sample_scene(plain, i), b = generate::sample_scene(varied, i);
    EXPECT_EQ(a.motion, a.motion_entry);
    EXPECT_EQ(a.motion_entry, b.motion_entry);  // the rest of the scene is drawn the same
    EXPECT_NE(a.motion, b.motion);
    EXPECT_EQ(a.shape.height, b.shape.height);
    EXPECT_EQ(a.wind_regime, b.wind_regime);
  }
}

// The message of the InputError reading `yaml` raises (config + check).
std::string refusal(const std::string& variation) {
  const std::string yaml = "name: bad\nbody:\n  motions: [procedural:walk]\n  variation: " + variation + "\n";
  try {
    auto config = cfg::read<generate::GeneratorConfig>(cfg::parse(yaml, "bad.yaml"));
    generate::check(config, "bad.yaml");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MotionVariation, BadValuesAreRefusedInOneLine) {
  const std::pair<const char*, const char*> cases[] = {{"{speed: [1.5, 1.0]}", "body.variation.speed"},
                                                       {"{speed: [0.1, 1.0]}", "body.variation.speed"},
                                                       {"{phase: [0, 1, 2]}", "body.variation.phase"},
                                                       {"{mirror: 2}", "body.variation.mirror"},
                                                       {"{clip_window: middle}", "body.variation.clip_window"},
                                                       {"{turn_angle: [0, 90]}", "body.variation.turn_angle"},
                                                       {"{pace: [1, 2]}", "pace"}};
  for (const auto& [bad, field] : cases) {
    const std::string what = refusal(bad);
    EXPECT_NE(what.find("bad.yaml"), std::string::npos) << bad << ": " << what;
    EXPECT_NE(what.find(field), std::string::npos) << bad << ": " << what;
    EXPECT_EQ(what.find('\n'), std::string::npos) << bad << ": " << what;
  }
  EXPECT_EQ(refusal("{speed: [1.0, 1.5], mirror: 0.5, clip_window: random}"), "");
}

}  // namespace
}  // namespace layers
