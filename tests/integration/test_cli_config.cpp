// `layers` CLI: global behaviour (help, exit codes) and the `config` verb.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "layers/core/text_file.h"
#include "run_command.h"
#include "temp_dir.h"

using layers::read_text_file;
using layers::test::layers_bin;
using layers::test::run_command;
using layers::test::TempDir;

TEST(CliGlobal, HelpAndUsageExitCodes) {
  auto help = run_command(layers_bin() + " --help");
  EXPECT_EQ(help.exit_code, 0);
  EXPECT_NE(help.output.find("Exit codes"), std::string::npos) << help.output;
  auto none = run_command(layers_bin());
  EXPECT_EQ(none.exit_code, 2) << none.output;
  auto unknown = run_command(layers_bin() + " frobnicate");
  EXPECT_EQ(unknown.exit_code, 2) << unknown.output;
  auto level = run_command(layers_bin() + " --log-level loud config --help");
  EXPECT_EQ(level.exit_code, 0) << level.output;  // --help wins over everything
}

TEST(CliConfig, PrintsResolvedConfigWithIncludesAndSets) {
  TempDir dir;
  dir.write("base.yaml", "run: {seed: 5, threads: 1}\nmodel: {name: static}\n");
  std::string exp = dir.write("exp.yaml", "include: base.yaml\nrun: {threads: 2}\n");
  std::string out = dir.file("resolved.yaml");
  auto r = run_command(layers_bin() + " config " + exp + " --set run.seed=9 --out " + out);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("seed: 9"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("threads: 2"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("device: cpu"), std::string::npos) << r.output;  // default filled in
  auto again = run_command(layers_bin() + " config " + out);
  EXPECT_EQ(again.exit_code, 0) << again.output;
}

// `layers config` knows every kind of config file; an experiment must name
// its model; flag values are checked, the empty one too.
TEST(CliConfig, ChecksGeneratorConfigsStudiesAndEmptyExperiments) {
  TempDir dir;
  const std::string src = layers::test::source_dir();
  auto gen = run_command(layers_bin() + " config " + src + "/configs/data/tiny.yaml --set sequences=4");
  EXPECT_EQ(gen.exit_code, 0) << gen.output;
  EXPECT_NE(gen.output.find("sequences: 4"), std::string::npos) << gen.output;
  auto bad_gen = run_command(layers_bin() + " config " + src + "/configs/data/tiny.yaml --set sim.substeps=-3");
  EXPECT_EQ(bad_gen.exit_code, 1) << bad_gen.output;
  EXPECT_NE(bad_gen.output.find("sim.substeps"), std::string::npos) << bad_gen.output;
  auto study = run_command(layers_bin() + " config " + src + "/configs/studies/compare_tiny.yaml");
  EXPECT_EQ(study.exit_code, 0) << study.output;
  EXPECT_NE(study.output.find("experiments:"), std::string::npos) << study.output;
  const std::string empty = dir.write("empty.yaml", "\n");
  auto e = run_command(layers_bin() + " config " + empty);
  EXPECT_EQ(e.exit_code, 1) << e.output;
  EXPECT_NE(e.output.find(empty + ": model: expected an experiment with a model section"), std::string::npos)
      << e.output;
  auto unset =
      run_command(layers_bin() + " config " + src + "/configs/experiments/layersnet_tiny.yaml --set train.epochs=");
  EXPECT_EQ(unset.exit_code, 1) << unset.output;
  EXPECT_NE(unset.output.find("train.epochs: expected a value after '='"), std::string::npos) << unset.output;
  auto level = run_command(layers_bin() + " --log-level bogus models");
  EXPECT_EQ(level.exit_code, 2) << level.output;
}

TEST(CliConfig, BadConfigExitsOneWithPreciseMessage) {
  TempDir dir;
  std::string bad = dir.write("bad.yaml", "run:\n  threads: 1000\n");
  auto r = run_command(layers_bin() + " config " + bad);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.output.find("bad.yaml:2: run.threads: expected an integer in [0, 256], got '1000'"), std::string::npos)
      << r.output;
  std::string malformed = dir.write("malformed.yaml", "run: {seed: 1\n");
  auto m = run_command(layers_bin() + " config " + malformed);
  EXPECT_EQ(m.exit_code, 1);
  EXPECT_NE(m.output.find("malformed YAML"), std::string::npos) << m.output;
  auto missing = run_command(layers_bin() + " config " + dir.file("nope.yaml"));
  EXPECT_EQ(missing.exit_code, 2) << missing.output;
}

// Every shipped config reads: a key renamed in the code, a file a study
// names that is gone, or a value out of range fails here, not in the
// middle of someone's experiment. The experiments' shared settings
// (configs/experiments/<dataset>.yaml, "# Shared settings ...") are read
// through the experiments that include them; a study is resolved run by
// run (`layers run --dry-run`: its experiments with their `set:` values),
// which writes nothing.
TEST(CliConfig, EveryShippedConfigReads) {
  const std::filesystem::path src = layers::test::source_dir();
  int checked = 0;
  for (const char* folder : {"configs/data", "configs/experiments", "configs/studies"}) {
    for (const auto& e : std::filesystem::directory_iterator(src / folder)) {
      if (e.path().extension() != ".yaml") continue;
      if (read_text_file(e.path().string()).rfind("# Shared settings", 0) == 0) continue;
      const bool study = std::string(folder) == "configs/studies";
      auto r = run_command(layers_bin() + (study ? " run --dry-run " : " config ") + e.path().string());
      EXPECT_EQ(r.exit_code, 0) << e.path() << "\n" << r.output;
      ++checked;
    }
  }
  EXPECT_GT(checked, 30);
}
