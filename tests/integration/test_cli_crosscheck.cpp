// `layers crosscheck` on a small synthetic dataset, without Blender: bad
// usage (exit 2), a missing Blender, an unknown sequence, a work folder
// that exists, a Blender that fails or writes nothing (exit 1, one line
// saying why, nothing of the user's overwritten); several scenes with a
// stand-in Blender: the summary, and a second run that resumes.
#include <gtest/gtest.h>

#include <filesystem>

#include "layers/data/dataset_writer.h"
#include "run_command.h"
#include "synthetic_sequence.h"
#include "temp_dir.h"

using namespace layers;
using test::run_command;

namespace {

std::string write_dataset(const test::TempDir& dir) {
  const std::string folder = dir.file("ds");
  data::DatasetWriterOptions options;
  options.name = "crosscheck-fixture";
  data::DatasetWriter writer(folder, options);
  data::testing::SyntheticSize size;
  size.frames = 4;
  writer.add(data::testing::make_sequence("a", 3, size));
  writer.add(data::testing::make_sequence("b", 4, size));
  writer.finish();
  return folder;
}

// A stand-in for Blender that "simulates" by copying the exported garment
// frames (so every Blender column equals our stored one) and reports 7 ms
// per frame.
std::string fake_blender(const test::TempDir& dir) {
  const std::string path = dir.write("fake-blender",
                                     "#!/bin/sh\n"
                                     "while [ \"$1\" != -- ]; do shift; done; shift\n"
                                     "while [ $# -gt 0 ]; do case \"$1\" in --scene) scene=$2; shift 2;; --out) "
                                     "out=$2; shift 2;; *) shift;; esac; done\n"
                                     "dir=$(dirname \"$scene\")\n"
                                     "prefix=$(sed -n 's/.*\"prefix\": \"\\([^\"]*\\)\".*/\\1/p' \"$scene\")\n"
                                     "for f in \"$dir/$prefix\"*.pc2; do m=$(basename \"$f\" .pc2); m=${m#$prefix}; "
                                     "[ \"$m\" = body ] || cp \"$f\" \"$out/$m.pc2\"; done\n"
                                     "echo 'ms_per_frame 7' > \"$out/timing.txt\"\n");
  std::filesystem::permissions(path, std::filesystem::perms::owner_all);
  return path;
}

std::string crosscheck(const std::string& args) { return test::layers_bin() + " crosscheck " + args; }

// The "layers: ..." line of the output (the error).
std::string error_line(const std::string& output) {
  const auto at = output.find("layers: ");
  return at == std::string::npos ? "" : output.substr(at, output.find('\n', at) - at);
}

}  // namespace

TEST(CliCrosscheck, BadUsageExitsTwo) {
  test::TempDir dir;
  const std::string ds = write_dataset(dir);
  auto setups = run_command(crosscheck(ds + " a --blender /bin/true --setups merged,other"));
  EXPECT_EQ(setups.exit_code, 2) << setups.output;
  EXPECT_NE(setups.output.find("--setups"), std::string::npos) << setups.output;
  auto frames = run_command(crosscheck(ds + " a --blender /bin/true --frames 1"));
  EXPECT_EQ(frames.exit_code, 2) << frames.output;
  auto missing = run_command(crosscheck(ds));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
}

TEST(CliCrosscheck, MissingBlenderIsOneLine) {
  test::TempDir dir;
  const std::string ds = write_dataset(dir);
  auto given = run_command(crosscheck(ds + " a --blender " + dir.file("no-blender")));
  EXPECT_EQ(given.exit_code, 1) << given.output;
  EXPECT_NE(error_line(given.output).find("not an executable"), std::string::npos) << given.output;
  auto on_path = run_command("env PATH=" + dir.path() + " LAYERS_BLENDER= " + crosscheck(ds + " a"));
  EXPECT_EQ(on_path.exit_code, 1) << on_path.output;
  EXPECT_NE(error_line(on_path.output).find("apt-get install blender"), std::string::npos) << on_path.output;
}

TEST(CliCrosscheck, UnknownSequenceAndFramesBeyondTheSequence) {
  test::TempDir dir;
  const std::string ds = write_dataset(dir);
  auto unknown = run_command(crosscheck(ds + " zz --blender /bin/true --work " + dir.file("w1")));
  EXPECT_EQ(unknown.exit_code, 1) << unknown.output;
  EXPECT_NE(error_line(unknown.output).find("zz"), std::string::npos) << unknown.output;
  auto frames = run_command(crosscheck(ds + " a --blender /bin/true --frames 5 --work " + dir.file("w2")));
  EXPECT_EQ(frames.exit_code, 1) << frames.output;
  EXPECT_NE(error_line(frames.output).find("2..4"), std::string::npos) << frames.output;
}

TEST(CliCrosscheck, ExistingWorkFolderIsRefusedAndKept) {
  test::TempDir dir;
  const std::string ds = write_dataset(dir);
  const std::string mine = dir.write("mine/notes.txt", "keep me");
  auto r = run_command(crosscheck(ds + " a --blender /bin/true --work " + dir.file("mine")));
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_NE(error_line(r.output).find("exists"), std::string::npos) << r.output;
  EXPECT_EQ(data::testing::read_text(mine), "keep me");
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.file("mine")), {}), 1);
}

TEST(CliCrosscheck, FailingOrSilentBlenderIsOneLine) {
  test::TempDir dir;
  const std::string ds = write_dataset(dir);
  auto failing = run_command(crosscheck(ds + " a --blender /bin/false --work " + dir.file("w1")));
  EXPECT_EQ(failing.exit_code, 1) << failing.output;
  EXPECT_NE(error_line(failing.output).find("Blender (merged) failed with exit status 1"), std::string::npos)
      << failing.output;
  // The export and the script are in the work folder for a look.
  EXPECT_TRUE(std::filesystem::exists(dir.file("w1/export/crosscheck.json")));
  EXPECT_TRUE(std::filesystem::exists(dir.file("w1/crosscheck_sim.py")));
  auto silent = run_command(crosscheck(ds + " a --blender /bin/true --setups separate --work " + dir.file("w2")));
  EXPECT_EQ(silent.exit_code, 1) << silent.output;
  EXPECT_NE(error_line(silent.output).find("Blender wrote no result"), std::string::npos) << silent.output;
}

TEST(CliCrosscheck, SeveralScenesGiveASummaryAndResume) {
  test::TempDir dir;
  const std::string ds = write_dataset(dir);
  const std::string blender = fake_blender(dir), work = dir.file("many");
  auto r = run_command(crosscheck(ds + " all --frames 4 --blender " + blender + " --work " + work));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("Cross-check over 2 scenes"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("| ms per frame | n/a | 7 ± 0 | 7 ± 0 |"), std::string::npos) << r.output;
  // Blender's frames are our stored ones: every paired difference is 0.
  EXPECT_NE(r.output.find("| layer crossings, mean over frames | 0.00 ± 0.00% | 0.00 ± 0.00% |"), std::string::npos)
      << r.output;
  for (const char* id : {"a", "b"}) {
    EXPECT_TRUE(std::filesystem::exists(work + "/" + id + "/columns.tsv")) << id;
    EXPECT_TRUE(std::filesystem::exists(work + "/" + id + "/table.md")) << id;
  }
  const std::string summary = data::testing::read_text(work + "/summary.md");

  // Scene b interrupted (no columns.tsv): a second run reads a back, runs
  // b again (its old folder moved aside, not deleted) and gives the same
  // summary.
  std::filesystem::remove(work + "/b/columns.tsv");
  auto again = run_command(crosscheck(ds + " a b --frames 4 --blender " + blender + " --work " + work));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("a (1 of 2) read back"), std::string::npos) << again.output;
  EXPECT_EQ(data::testing::read_text(work + "/summary.md"), summary);
  int aside = 0;
  for (const auto& e : std::filesystem::directory_iterator(work))
    aside += e.path().filename().string().rfind("b.replaced-", 0) == 0;
  EXPECT_EQ(aside, 1);

  // Issue 62 S7: resumed with other --frames, the scenes read back were
  // averaged in under the new count; now refused, the folder unchanged.
  auto frames = run_command(crosscheck(ds + " a b --frames 3 --blender " + blender + " --work " + work));
  EXPECT_EQ(frames.exit_code, 1) << frames.output;
  EXPECT_NE(error_line(frames.output)
                .find("a/columns.tsv: ours (stored) frames: expected 2 measured frames, as "
                      "--frames 3 gives"),
            std::string::npos)
      << frames.output;
  EXPECT_EQ(data::testing::read_text(work + "/summary.md"), summary);

  // A folder of another dataset's run is refused.
  const std::string other = dir.write("other/scenes.txt", "dataset /elsewhere\n");
  auto refused = run_command(crosscheck(ds + " a b --blender " + blender + " --work " + dir.file("other")));
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_NE(error_line(refused.output).find("not a cross-check of several scenes of this dataset"), std::string::npos)
      << refused.output;
}
