// Scene sampling: held-out motions and outfits leave train/val/test and are
// tagged unseen_motion / unseen_garment; everything else is unchanged.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/generate/generator_config.h"
#include "layers/generate/scene_spec.h"
#include "test_paths.h"

namespace layers {
namespace {

generate::GeneratorConfig small_config() {
  auto config = cfg::read<generate::GeneratorConfig>(
      cfg::load_file(test::source_dir() + "/configs/data/small_tables.yaml"), "small");
  config.splits.unseen_motions.clear();
  config.splits.unseen_outfits.clear();
  return config;
}

bool has_tag(const generate::SceneSpec& s, const std::string& tag) {
  return std::find(s.tags.begin(), s.tags.end(), tag) != s.tags.end();
}

TEST(SceneSpec, HeldOutScenesLeaveTheSplitsAndOthersStayTheSame) {
  const generate::GeneratorConfig plain = small_config();
  generate::GeneratorConfig held = plain;
  held.splits.unseen_motions = {"procedural:jump"};
  held.splits.unseen_outfits = {generate::outfit_label(plain.garments.outfits.at(4))};
  EXPECT_EQ(held.splits.unseen_outfits[0], "dress_belt/jacket");
  generate::check(held, "small.yaml");
  int motions = 0, outfits = 0;
  for (int i = 0; i < plain.sequences; ++i) {
    const generate::SceneSpec a = generate::sample_scene(plain, i), b = generate::sample_scene(held, i);
    // The scene itself does not change, only where it is filed.
    EXPECT_EQ(a.motion, b.motion);
    ASSERT_EQ(a.garments.size(), b.garments.size());
    for (std::size_t g = 0; g < a.garments.size(); ++g) EXPECT_EQ(a.garments[g].type, b.garments[g].type);
    EXPECT_FALSE(a.split.empty());
    const bool jump = b.motion == "procedural:jump";
    const bool belt = b.garments.front().type == "dress_belt";
    EXPECT_EQ(has_tag(b, "unseen_motion"), jump) << b.id;
    EXPECT_EQ(has_tag(b, "unseen_garment"), belt) << b.id;
    EXPECT_EQ(b.split.empty(), jump || belt) << b.id;
    if (!jump && !belt) {
      EXPECT_EQ(a.split, b.split);
    }
    motions += jump;
    outfits += belt;
  }
  EXPECT_GT(motions, 0);
  EXPECT_GT(outfits, 0);
}

TEST(SceneSpec, UnknownOrExhaustiveHoldoutsAreRejectedByName) {
  generate::GeneratorConfig config = small_config();
  config.splits.unseen_motions = {"procedural:moonwalk"};
  try {
    generate::check(config, "small.yaml");
    FAIL() << "accepted an unknown motion";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("splits.unseen_motions[0]"), std::string::npos) << what;
    EXPECT_NE(what.find("moonwalk"), std::string::npos) << what;
  }
  config.splits.unseen_motions.clear();
  for (const auto& o : config.garments.outfits) config.splits.unseen_outfits.push_back(generate::outfit_label(o));
  EXPECT_THROW(generate::check(config, "small.yaml"), InputError);
}

}  // namespace
}  // namespace layers
