// tests/adversarial/test_adversarial_doors.cpp -- issue 62's cases of the
// doors added after issue 44's probe, through the `layers` binary: every
// output path is new and none of the command's inputs (D2 `stats --out`
// into the dataset, D3 `body --out` onto an existing shard, D4 `config
// --out` onto its own input, D5 `export` onto same-named files, D6
// `generate --out` into a folder of the user's files). Each ends
// with exit 1 and one line naming the path and the flag, and changes
// nothing on disk.
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <algorithm>
#include <filesystem>

#include "adversarial_fixture.h"
#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;

namespace {

class Doors : public ::testing::Test {
 protected:
  // `args` refused with exit 1 and one line holding `expect`, the files
  // under `watched` unchanged.
  void refused(const std::string& args, const std::string& watched, const std::string& expect) {
    const auto before = test::snapshot(watched);
    const auto r = test::run_command(test::layers_bin() + " " + args);
    EXPECT_EQ(r.exit_code, 1) << args << "\n" << r.output;
    EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << args << "\n" << r.output;
    EXPECT_NE(r.output.find(expect), std::string::npos) << args << "\n" << r.output;
    EXPECT_EQ(test::snapshot(watched), before) << args << " changed " << watched;
  }
  test::TempDir dir_{"layers-doors"};
};

TEST_F(Doors, D2_StatsOutIntoTheDatasetIsRefused) {
  const std::string data = test::write_two_shards(dir_.file("data"));
  refused("stats " + data + " --out " + data + "/shard-00000.h5", data,
          "--out: expected a path outside the command's inputs (an input is never an output), got a path inside "
          "the input");
  refused("stats " + data + " --out " + data + "/other.h5", data, "a path inside the input");
  // A new file elsewhere is written.
  const auto ok = test::run_command(test::layers_bin() + " stats " + data + " --out " + dir_.file("s.h5"));
  EXPECT_EQ(ok.exit_code, 0) << ok.output;
  EXPECT_TRUE(fs::exists(dir_.file("s.h5")));
  refused("stats " + data + " --out " + dir_.file("s.h5"), dir_.path(),
          "--out: expected a new path (nothing is overwritten; move or delete it first), got an existing file");
}

TEST_F(Doors, D3_BodyOutOntoAnExistingFileIsRefused) {
  const std::string shard = dir_.write("mine.h5", "the user's file");
  refused("body --frames 3 --transition 1 --out " + shard, dir_.path(), "mine.h5: --out: expected a new path");
}

TEST_F(Doors, D4_ConfigOutOntoItsOwnInputIsRefused) {
  const std::string config = test::source_dir() + "/configs/data/tiny.yaml";
  const std::string copy = dir_.file("tiny.yaml");
  fs::copy_file(config, copy);
  refused("config " + copy + " --out " + copy, dir_.path(), "got the input " + copy);
  const std::string mine = dir_.write("resolved.yaml", "mine\n");
  refused("config " + copy + " --out " + mine, dir_.path(), "got an existing file");
}

TEST_F(Doors, D5_ExportOntoSameNamedFilesIsRefused) {
  const std::string data = test::write_two_shards(dir_.file("data"));
  const std::string out = dir_.file("export");
  const auto first = test::run_command(test::layers_bin() + " export " + data + " seq0 --format glb --out " + out);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  refused("export " + data + " seq0 --format glb --out " + out, out,
          "seq0.glb: expected a name not taken in the output folder (an export replaces nothing)");
  // Another sequence into the same folder is fine.
  const auto other = test::run_command(test::layers_bin() + " export " + data + " seq1 --format glb --out " + out);
  EXPECT_EQ(other.exit_code, 0) << other.output;
}

TEST_F(Doors, D6_GenerateIntoAFolderOfOtherFilesIsRefusedBeforeSimulating) {
  const std::string out = dir_.file("mine");
  dir_.write("mine/splits.yaml", "the user's splits\n");
  refused("generate --config " + test::source_dir() + "/configs/data/tiny.yaml --set sequences=1 --out " + out, out,
          "mine: --out: expected a new or empty folder, or a dataset folder a generation with this config started "
          "(generator.yaml), got a folder holding other files");
}

// S9: a dataset whose splits.yaml has no train split was refused by
// validate but read by the other verbs.
TEST_F(Doors, S9_ADatasetWithoutATrainSplitIsRefusedByEveryReader) {
  const std::string data = test::write_two_shards(dir_.file("data"));
  dir_.write("data/splits.yaml", "val: [seq3]\ntest: [seq4, seq5]\n");
  for (const std::string& verb : {"info " + data, "export " + data + " seq3 --format glb --out " + dir_.file("x")})
    refused(verb, data, "splits.yaml: train: expected a train split (statistics come from it), got none");
  EXPECT_FALSE(fs::exists(dir_.file("x")));
}

// Unclear message 6: /dev/null as a dataset was "no HDF5 signature (...,
// 18446744073709551615 bytes)"; a FIFO would have hung in libhdf5.
TEST_F(Doors, U6_ADeviceOrPipeAsADatasetSaysWhatItIs) {
  const std::string fifo = dir_.file("pipe.h5");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  for (const std::string& path : {std::string("/dev/null"), fifo})
    refused("info " + path, dir_.path(), path + ": expected an HDF5 file, got a pipe, socket or device");
}

}  // namespace
