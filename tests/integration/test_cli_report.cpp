// `layers report --out` onto a folder that holds a report: refused with
// one line and nothing changed; with --force the old folder is moved
// aside, never deleted; the folder the command runs in is never moved.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "layers/core/text_file.h"
#include "run_command.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;
using test::run_command;

TEST(CliReport, AFolderHoldingAReportIsReplacedOnlyWithForceAndMovedAside) {
  test::TempDir dir;
  const fs::path out = dir.file("out");
  fs::create_directories(out);
  std::ofstream(out / "report.md") << "my notes\n";
  const std::string report = test::layers_bin() + " report --no-charts --runs " + dir.file("no-run") + " --out ";

  auto refused = run_command(report + out.string());
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_NE(refused.output.find("--out: expected a new folder, or --force"), std::string::npos) << refused.output;
  EXPECT_EQ(read_text_file((out / "report.md").string()), "my notes\n");
  EXPECT_FALSE(fs::exists(out / "summary.csv"));

  // --force: the old folder moved aside, a new report written (exit 1: no
  // run had an evaluation).
  auto forced = run_command(report + out.string() + " --force");
  EXPECT_NE(forced.output.find("moved the old report"), std::string::npos) << forced.output;
  std::vector<fs::path> aside;
  for (const auto& e : fs::directory_iterator(dir.path()))
    if (e.path().filename().string().rfind("out.replaced-", 0) == 0) aside.push_back(e.path());
  ASSERT_EQ(aside.size(), 1u) << forced.output;
  EXPECT_EQ(read_text_file((aside[0] / "report.md").string()), "my notes\n");
  EXPECT_TRUE(fs::exists(out / "summary.csv"));

  // The folder the command runs in is not moved.
  auto here = run_command("cd " + out.string() + " && " + report + ". --force");
  EXPECT_EQ(here.exit_code, 1) << here.output;
  EXPECT_NE(here.output.find("a folder other than the current one"), std::string::npos) << here.output;
  EXPECT_TRUE(fs::exists(out / "summary.csv"));

  // Issue 62 D1: a folder of the user's files without report.md was
  // replaced; now refused, kept as it was.
  const fs::path mine = dir.file("mine");
  fs::create_directories(mine);
  std::ofstream(mine / "thesis.tex") << "chapter 1\n";
  auto kept = run_command(report + mine.string());
  EXPECT_EQ(kept.exit_code, 1) << kept.output;
  EXPECT_NE(kept.output.find("mine: --out: expected a new path (nothing is overwritten"), std::string::npos)
      << kept.output;
  EXPECT_EQ(read_text_file((mine / "thesis.tex").string()), "chapter 1\n");
  EXPECT_FALSE(fs::exists(mine / "summary.csv"));
}
