// `layers` CLI on a small synthetic dataset made in the test: info,
// validate (good and broken), stats, export.
#include <gtest/gtest.h>

#include <filesystem>

#include "layers/data/dataset.h"
#include "layers/data/dataset_writer.h"
#include "layers/data/pc2.h"
#include "layers/data/stats.h"
#include "run_command.h"
#include "synthetic_sequence.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

namespace {

// A three-sequence dataset (train: a, b; test: c) in `folder`.
void write_dataset(const std::string& folder) {
  data::DatasetWriterOptions options;
  options.name = "cli-fixture";
  options.sequences_per_shard = 2;
  data::DatasetWriter writer(folder, options);
  for (const char* id : {"a", "b", "c"}) writer.add(data::testing::make_sequence(id, id[0]));
  writer.set_split("train", {"a", "b"});
  writer.set_split("test", {"c"});
  writer.finish();
  data::write_dataset_stats(folder, data::compute_stats(data::Dataset::open(folder)));  // as the generator does
}

}  // namespace

TEST(CliData, InfoListsSequencesGarmentsAndSplits) {
  test::TempDir dir;
  write_dataset(dir.file("ds"));
  auto r = run_command(test::layers_bin() + " info " + dir.file("ds"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("dataset   cli-fixture"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("sequences 3  frames 36  garments 6"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("train=2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("test=1"), std::string::npos) << r.output;
  auto one = run_command(test::layers_bin() + " info " + dir.file("ds") + " --sequence b");
  ASSERT_EQ(one.exit_code, 0) << one.output;
  EXPECT_NE(one.output.find("128 vertices"), std::string::npos) << one.output;
  auto shard = run_command(test::layers_bin() + " info " + dir.file("ds/shard-00001.h5"));
  ASSERT_EQ(shard.exit_code, 0) << shard.output;
  EXPECT_NE(shard.output.find("sequences 1"), std::string::npos) << shard.output;
  auto missing = run_command(test::layers_bin() + " info " + dir.file("ds") + " --sequence zz");
  EXPECT_EQ(missing.exit_code, 1) << missing.output;
  EXPECT_NE(missing.output.find("zz"), std::string::npos) << missing.output;
}

TEST(CliData, ValidateReportsEveryProblemAndExitsOne) {
  test::TempDir dir;
  write_dataset(dir.file("ds"));
  auto good = run_command(test::layers_bin() + " validate " + dir.file("ds"));
  EXPECT_EQ(good.exit_code, 0) << good.output;
  EXPECT_NE(good.output.find("valid LAYERS-H5"), std::string::npos) << good.output;

  data::testing::poke<float>(dir.file("ds/shard-00000.h5"), "/seq/a/garments/0/positions", {3, 5, 1}, NAN);
  data::testing::write_text(dir.file("ds/splits.yaml"), "train: [a, b, ghost]\ntest: [c]\n");
  auto bad = run_command(test::layers_bin() + " validate " + dir.file("ds"));
  EXPECT_EQ(bad.exit_code, 1) << bad.output;
  EXPECT_NE(bad.output.find("/seq/a/garments/0/positions"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("ghost"), std::string::npos) << bad.output;
  EXPECT_NE(bad.output.find("2 problems"), std::string::npos) << bad.output;

  auto notfound = run_command(test::layers_bin() + " validate " + dir.file("nothing"));
  EXPECT_EQ(notfound.exit_code, 1) << notfound.output;
}

TEST(CliData, StatsWritesStatsFileFromTrain) {
  test::TempDir dir;
  write_dataset(dir.file("ds"));
  auto r = run_command(test::layers_bin() + " stats " + dir.file("ds"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("split 'train': 2 sequences, 24 frames"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::exists(dir.file("ds/stats.h5")));
  auto empty = run_command(test::layers_bin() + " stats " + dir.file("ds") + " --split val");
  EXPECT_EQ(empty.exit_code, 1) << empty.output;
  EXPECT_NE(empty.output.find("val"), std::string::npos) << empty.output;
}

TEST(CliData, ExportObjAndPc2) {
  test::TempDir dir;
  write_dataset(dir.file("ds"));
  auto obj = run_command(test::layers_bin() + " export " + dir.file("ds") + " b --format obj --frames 2:5 --out " +
                         dir.file("obj"));
  ASSERT_EQ(obj.exit_code, 0) << obj.output;
  // body + 2 garments, 3 frames each.
  EXPECT_NE(obj.output.find("wrote 9 files"), std::string::npos) << obj.output;
  auto pc2 = run_command(test::layers_bin() + " export " + dir.file("ds") + " b --format pc2 --frames 1: --out " +
                         dir.file("pc2"));
  ASSERT_EQ(pc2.exit_code, 0) << pc2.output;
  int caches = 0;
  for (const auto& entry : fs::directory_iterator(dir.file("pc2"))) {
    if (entry.path().extension() != ".pc2") continue;
    ++caches;
    EXPECT_EQ(data::read_pc2_header(entry.path().string()).n_samples, 11) << entry.path();
  }
  EXPECT_EQ(caches, 3);
  auto bad_format = run_command(test::layers_bin() + " export " + dir.file("ds") + " b --format fbx");
  EXPECT_EQ(bad_format.exit_code, 1) << bad_format.output;
  EXPECT_NE(bad_format.output.find("--format"), std::string::npos) << bad_format.output;
  auto bad_range = run_command(test::layers_bin() + " export " + dir.file("ds") + " b --frames 5:2");
  EXPECT_EQ(bad_range.exit_code, 1) << bad_range.output;
  auto past_end =
      run_command(test::layers_bin() + " export " + dir.file("ds") + " b --frames 10:40 --out " + dir.file("x"));
  EXPECT_EQ(past_end.exit_code, 1) << past_end.output;
}
