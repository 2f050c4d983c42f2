// What the report says about selection and seeds, on run folders the test
// writes: which split chose each checkpoint and which it is evaluated on,
// the mark on a run chosen on the test split (or on the evaluated split),
// evaluations made before the record ("unknown", never a crash), and the
// mean and std over the seeds of a study experiment's seed-<s> runs, and the
// paired per-sequence comparisons of learned rows with references and partners.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

#include "layers/core/text_file.h"
#include "layers/report/paired.h"
#include "layers/report/report.h"
#include "layers/report/seeds.h"
#include "report_fixtures.h"

namespace layers::report {
namespace {

using layers::test::TempDir;
using testing::FakeRun;

// The CSV's rows as maps from column name to cell (no quoted commas here).
std::vector<std::map<std::string, std::string>> csv_rows(const std::string& text) {
  std::stringstream in(text);
  auto cells = [](const std::string& line) {
    std::vector<std::string> out;
    std::stringstream s(line);
    for (std::string c; std::getline(s, c, ',');) out.push_back(c);
    if (!line.empty() && line.back() == ',') out.push_back("");
    return out;
  };
  std::string line;
  std::getline(in, line);
  const std::vector<std::string> header = cells(line);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(in, line)) {
    const std::vector<std::string> c = cells(line);
    std::map<std::string, std::string> row;
    for (std::size_t i = 0; i < header.size() && i < c.size(); ++i) row[header[i]] = c[i];
    rows.push_back(row);
  }
  return rows;
}

ReportInputs tables_only(const std::vector<std::string>& runs) {
  ReportInputs inputs;
  inputs.runs = runs;
  inputs.charts = false;
  return inputs;
}

TEST(Selection, ReportSaysWhichSplitChoseWhatAndMarksTheTestSplit) {
  TempDir dir("report-selection");
  FakeRun fair, peek, same, old;
  fair.chosen_on = "val";
  peek.chosen_on = "test";  // a checkpoint chosen on the test split
  same.chosen_on = "val", same.evaluated_on = "val";
  // `old` has no record: evaluated before metrics.json carried it.
  const std::vector<std::string> runs = {testing::write_run(dir, "fair", fair), testing::write_run(dir, "peek", peek),
                                         testing::write_run(dir, "same", same), testing::write_run(dir, "old", old)};
  // The trainer's selection.json gives the chosen epoch's validation error;
  // one that is not a number is a problem of that run, not a crash.
  std::ofstream(runs[0] + "/selection.json") << R"({"chosen_on": "val", "best_val_error_mm": 11.25})";
  std::ofstream(runs[1] + "/selection.json") << R"({"best_val_error_mm": "low"})";

  const RunResults loaded = load_run(runs[0]);
  ASSERT_TRUE(loaded.eval);
  EXPECT_EQ(loaded.eval->selection.checkpoint, "best");
  EXPECT_EQ(loaded.eval->selection.chosen_on, "val");
  EXPECT_EQ(loaded.eval->selection.evaluated_on, "test");
  EXPECT_EQ(loaded.eval->selection.chosen_epoch, 2);
  EXPECT_DOUBLE_EQ(loaded.eval->selection.val_error_mm, 11.25);
  EXPECT_EQ(selection_flag(loaded), "");
  const RunResults bad_record = load_run(runs[1]);
  EXPECT_TRUE(std::isnan(bad_record.eval->selection.val_error_mm));
  bool named = false;
  for (const std::string& p : bad_record.problems) named = named || p.find("best_val_error_mm") != std::string::npos;
  EXPECT_TRUE(named) << "no problem names best_val_error_mm";
  const RunResults unknown = load_run(runs[3]);
  ASSERT_TRUE(unknown.eval);
  EXPECT_EQ(unknown.eval->selection.chosen_on, "unknown");
  EXPECT_EQ(unknown.eval->selection.evaluated_on, "test");
  EXPECT_EQ(selection_flag(unknown), "");
  EXPECT_NE(selection_flag(load_run(runs[1])).find("test split"), std::string::npos);
  EXPECT_NE(selection_flag(load_run(runs[2])).find("evaluated on"), std::string::npos);
  // Captions name the splits the figures are over, not always "test".
  EXPECT_EQ(evaluated_sequences({load_run(runs[2])}), "the val sequences");
  EXPECT_EQ(evaluated_sequences({load_run(runs[0]), load_run(runs[2]), load_run(runs[1])}),
            "each run's evaluated sequences (test or val)");
  EXPECT_EQ(evaluated_sequences({}), "the evaluated sequences");
  // A chart's caption speaks of the runs it plots only.
  const std::vector<RunResults> three{load_run(runs[0]), load_run(runs[2]), load_run(runs[1])};
  EXPECT_EQ(evaluated_sequences(three, {1}), "the val sequences");
  EXPECT_EQ(evaluated_sequences(three, {0, 2}), "the test sequences");

  const ReportResult r = write_report(tables_only(runs), dir.file("out"));
  EXPECT_EQ(r.runs_with_metrics, 4u);
  ASSERT_EQ(r.selection_flags.size(), 2u);
  EXPECT_EQ(r.selection_flags[0].rfind("peek: ", 0), 0u) << r.selection_flags[0];
  EXPECT_EQ(r.selection_flags[1].rfind("same: ", 0), 0u) << r.selection_flags[1];

  const std::string md = read_text_file(r.report);
  EXPECT_NE(md.find("**⚠ Selection:** 2 runs"), std::string::npos) << md;
  EXPECT_NE(md.find("| peek **⚠ chosen on the test split (test)** | mymodel |"), std::string::npos) << md;
  EXPECT_NE(md.find("| same **⚠ chosen on val, the split evaluated** | mymodel |"), std::string::npos) << md;
  EXPECT_NE(md.find("| fair | mymodel |"), std::string::npos) << md;
  EXPECT_NE(md.find("### Selection"), std::string::npos);
  EXPECT_NE(md.find("| fair | best | val | 2 / 3 | mean rollout error (mm) | 11.25 | test |  |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| old | unknown | unknown | - / - | - | - | test |  |"), std::string::npos) << md;

  const auto rows = csv_rows(read_text_file(dir.file("out/summary.csv")));
  ASSERT_EQ(rows.size(), 4u);
  EXPECT_EQ(rows[0].at("chosen_on"), "val");
  EXPECT_EQ(rows[0].at("evaluated_on"), "test");
  EXPECT_EQ(rows[0].at("selection_flag"), "");
  EXPECT_EQ(rows[0].at("val_error_mm"), "11.25");
  EXPECT_EQ(rows[2].at("val_error_mm"), "");
  EXPECT_EQ(rows[1].at("chosen_on"), "test");
  EXPECT_NE(rows[1].at("selection_flag"), "");
  EXPECT_EQ(rows[3].at("checkpoint"), "unknown");
  const nlohmann::json summary = nlohmann::json::parse(read_text_file(dir.file("out/summary.json")));
  EXPECT_EQ(summary["runs"][1]["selection"]["chosen_on"], "test");
  EXPECT_DOUBLE_EQ(summary["runs"][0]["selection"]["val_error_mm"].get<double>(), 11.25);
  EXPECT_TRUE(summary["runs"][2]["selection"]["val_error_mm"].is_null());
  EXPECT_NE(summary["runs"][1]["selection"]["flag"].get<std::string>(), "");
}

TEST(Seeds, MeanAndStdOverSeedsBesideTheSpreadOverSequences) {
  TempDir dir("report-seeds");
  // A study experiment over three seeds (<name>/seed-<s>) and a plain run.
  const double errors[] = {10.0, 12.0, 14.0}, spreads[] = {1.0, 2.0, 3.0}, h[] = {0.01, 0.02, 0.03};
  for (int k = 0; k < 3; ++k) {
    FakeRun run;
    run.error = errors[k], run.error_std = spreads[k], run.h = h[k], run.ms_per_frame = 1.0 + k;
    run.chosen_on = "val";
    testing::write_run(dir, "net/seed-" + std::to_string(k), run);
  }
  FakeRun plain;
  plain.chosen_on = "val";
  testing::write_run(dir, "plain", plain);

  // The experiment's folder stands for its seeds.
  const ReportResult r = write_report(tables_only({dir.file("net"), dir.file("plain")}), dir.file("out"));
  EXPECT_EQ(r.runs_with_metrics, 4u);

  std::vector<RunResults> runs;
  for (const std::string& d : expand_seed_folders({dir.file("net"), dir.file("plain")})) runs.push_back(load_run(d));
  ASSERT_EQ(runs.size(), 4u);
  EXPECT_EQ(runs[1].name, "net/seed-1");
  EXPECT_EQ(runs[1].experiment, "net");
  EXPECT_TRUE(runs[1].repeated);
  EXPECT_EQ(runs[1].seed, 1u);
  EXPECT_FALSE(runs[3].repeated);
  const std::vector<SeedGroup> groups = seed_groups(runs);
  ASSERT_EQ(groups.size(), 1u);
  const SeedGroup& g = groups[0];
  EXPECT_EQ(g.experiment, "net");
  EXPECT_EQ(g.seeds, (std::vector<std::uint64_t>{0, 1, 2}));
  const double std_over_seeds = 2.0;  // sample std (n - 1) of 10, 12, 14
  EXPECT_NEAR(g.over_seeds.get("error_mm").mean, 12.0, 1e-9);
  EXPECT_NEAR(g.over_seeds.get("error_mm").std, std_over_seeds, 1e-9);
  EXPECT_EQ(g.over_seeds.get("error_mm").count, 3);
  EXPECT_NEAR(g.over_sequences.get("error_mm").mean, 2.0, 1e-9);  // mean of the seeds' stds over sequences
  EXPECT_NEAR(g.over_seeds.get("h_collision").mean, 0.02, 1e-9);
  EXPECT_NEAR(g.over_seeds.get("h_collision").std, 0.01, 1e-9);
  EXPECT_NEAR(g.ms_per_frame, 2.0, 1e-9);

  const std::string md = read_text_file(r.report);
  EXPECT_NE(md.find("| net (3 seeds) | mymodel | 1234 | test (2) | 12.0 ± 2.0 (sequences ± 2.0) | 2.00% ± 1.00 |"),
            std::string::npos)
      << md;
  EXPECT_EQ(md.find("| net/seed-1 | mymodel"), std::string::npos) << "seed rows are collapsed in the models table";
  EXPECT_NE(md.find("- `net` per seed, error (mm): seed 0 10.0, seed 1 12.0, seed 2 14.0"), std::string::npos) << md;
  EXPECT_NE(md.find("| plain | mymodel |"), std::string::npos) << md;

  // Seeds of one experiment kept in different folders (a study run in
  // parts) are one experiment when their settings match; an experiment of
  // the same name with other settings is not.
  FakeRun part;
  part.chosen_on = "val";
  testing::write_run(dir, "part-1/net/seed-0", part);
  testing::write_run(dir, "part-2/net/seed-1", part);
  FakeRun other = part;
  other.model = "othermodel";
  testing::write_run(dir, "part-3/net/seed-2", other);
  std::vector<RunResults> parts;
  for (const char* d : {"part-1/net/seed-0", "part-2/net/seed-1", "part-3/net/seed-2"})
    parts.push_back(load_run(dir.file(d)));
  const std::vector<SeedGroup> across = seed_groups(parts);
  ASSERT_EQ(across.size(), 1u);
  EXPECT_EQ(across[0].seeds, (std::vector<std::uint64_t>{0, 1}));

  const auto seeds = csv_rows(read_text_file(dir.file("out/seeds.csv")));
  ASSERT_EQ(seeds.size(), 1u);
  EXPECT_EQ(seeds[0].at("experiment"), "net");
  EXPECT_EQ(seeds[0].at("seeds"), "3");
  EXPECT_EQ(seeds[0].at("seed_list"), "0 1 2");
  EXPECT_NEAR(std::stod(seeds[0].at("error_mm")), 12.0, 1e-6);
  EXPECT_NEAR(std::stod(seeds[0].at("error_mm_std_seeds")), std_over_seeds, 1e-6);
  EXPECT_NEAR(std::stod(seeds[0].at("error_mm_std_sequences")), 2.0, 1e-6);
  // Each seed's values stay in summary.csv.
  const auto summary = csv_rows(read_text_file(dir.file("out/summary.csv")));
  ASSERT_EQ(summary.size(), 4u);
  EXPECT_EQ(summary[2].at("run"), "net/seed-2");
  EXPECT_EQ(summary[2].at("experiment"), "net");
  EXPECT_EQ(summary[2].at("seed"), "2");
  EXPECT_NEAR(std::stod(summary[2].at("error_mm")), 14.0, 1e-6);
  EXPECT_EQ(summary[3].at("seed"), "");
}

// Paired comparisons: each learned row against the reference rows and its
// partner, per sequence, with the hand-worked 95% interval.
TEST(Paired, LearnedRowsAgainstReferencesAndPartnersPerSequence) {
  TempDir dir("report-paired");
  const std::vector<double> skinned = {10, 12, 14, 16, 18};
  FakeRun reference;
  reference.model = "skinned";
  reference.parameters = 0;
  reference.sequence_errors = skinned;
  testing::write_run(dir, "skinned", reference);
  // `good`: lower than skinned on every sequence by 1.0, 1.2, 0.8, 1.1, 0.9.
  FakeRun good;
  good.sequence_errors = {9.0, 10.8, 13.2, 14.9, 17.1};
  testing::write_run(dir, "good", good);
  // `mixed` over two seeds whose mean per sequence is skinned + 1, -1, 2,
  // -2, 0.5: two lower, three higher, mean +0.1.
  const std::vector<double> offsets = {1, -1, 2, -2, 0.5};
  for (int seed = 0; seed < 2; ++seed) {
    FakeRun run;
    run.model = "mixedmodel";
    run.sequence_errors.clear();
    for (std::size_t k = 0; k < skinned.size(); ++k)
      run.sequence_errors.push_back(skinned[k] + offsets[k] + (seed == 0 ? 0.25 : -0.25));
    testing::write_run(dir, "mixed/seed-" + std::to_string(seed), run);
  }
  ReportInputs inputs = tables_only({dir.file("skinned"), dir.file("good"), dir.file("mixed")});
  inputs.partners = {{"mixed", "good"}, {"good", "absent"}};
  const ReportResult r = write_report(inputs, dir.file("out"));

  std::vector<RunResults> runs;
  for (const std::string& d : expand_seed_folders(inputs.runs)) runs.push_back(load_run(d));
  std::vector<std::string> missing;
  const std::vector<PairedComparison> paired = paired_comparisons(runs, inputs.partners, &missing);
  ASSERT_EQ(paired.size(), 3u);
  const PairedComparison& g = paired[0];
  EXPECT_EQ(g.row, "good");
  EXPECT_EQ(g.against, "skinned");
  EXPECT_EQ(g.why, "reference");
  EXPECT_EQ(g.difference.n, 5u);
  EXPECT_NEAR(g.difference.mean, -1.0, 1e-9);
  // Differences -1, -1.2, -0.8, -1.1, -0.9: sample sd sqrt(0.1 / 4), t(4) = 2.776.
  EXPECT_NEAR(g.difference.sd, std::sqrt(0.025), 1e-9);
  EXPECT_NEAR(g.difference.half_width, 2.776 * std::sqrt(0.025) / std::sqrt(5.0), 1e-3);
  EXPECT_EQ(g.wins, 5u);
  EXPECT_EQ(g.losses, 0u);
  EXPECT_EQ(g.reading(), "lower");
  const PairedComparison& m = paired[1];
  EXPECT_EQ(m.row, "mixed");
  EXPECT_EQ(m.against, "skinned");
  EXPECT_NEAR(m.difference.mean, 0.1, 1e-9);
  EXPECT_EQ(m.wins, 2u);
  EXPECT_EQ(m.losses, 3u);
  EXPECT_EQ(m.reading(), "not separated");
  // With its seeds: seed means over the 5 sequences differ by 0.5 (+0.25
  // and -0.25 around the mean), so the variance over seeds is 0.125 and
  // adds 0.125 / 2 to sd^2 / n = 2.55 / 5; Satterthwaite's df
  // 0.5725^2 / (0.51^2 / 4 + 0.0625^2 / 1) = 4.76, taken as 4.
  EXPECT_EQ(m.row_seeds, 2u);
  EXPECT_EQ(m.against_seeds, 0u);
  ASSERT_TRUE(m.with_seeds);
  EXPECT_NEAR(m.seeds_se, std::sqrt(0.51 + 0.0625), 1e-9);
  EXPECT_NEAR(m.seeds_df, 0.5725 * 0.5725 / (0.51 * 0.51 / 4 + 0.0625 * 0.0625), 1e-9);
  EXPECT_NEAR(m.seeds_half_width, 2.776 * std::sqrt(0.5725), 1e-9);
  EXPECT_NEAR(m.p_value, t_two_sided_p(0.1 / std::sqrt(0.5725), 4), 1e-12);
  // `good` has one seed: no seed interval; the reference rows have none to add.
  EXPECT_FALSE(g.with_seeds);
  EXPECT_FALSE(paired[2].with_seeds) << "one seed of good beside two of mixed";
  // Holm over the 3: good - skinned (t = -14.1, df 4, p ~ 1.5e-4) stays
  // separated; mixed - good (p ~ 0.17) was not separated anyway.
  EXPECT_LT(g.p_value, 0.05 / 3);
  EXPECT_TRUE(g.holm);
  EXPECT_EQ(g.holm_reading(), "lower");
  EXPECT_FALSE(m.holm);
  EXPECT_EQ(paired[2].row, "mixed");
  EXPECT_EQ(paired[2].against, "good");
  EXPECT_EQ(paired[2].why, "partner");
  EXPECT_EQ(paired[2].wins, 1u) << "only on s4 is mixed (14) below good (14.9)";
  ASSERT_EQ(missing.size(), 1u);
  EXPECT_EQ(missing[0], "good: partner absent is not in the report");

  const std::string md = read_text_file(r.report);
  EXPECT_NE(md.find("### Paired comparisons (error per sequence)"), std::string::npos) << md;
  EXPECT_NE(md.find("| `good` | `skinned` | test (5) | -1.00 [-1.20, -0.80] | - (1 / -) | 5 / 0 | <0.001 | **lower "
                    "error** | **lower error** |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| `mixed` | `good` (partner) | test (5) |"), std::string::npos) << md;
  EXPECT_NE(md.find("paired comparisons: good: partner absent is not in the report"), std::string::npos) << md;
  const auto csv = csv_rows(read_text_file(dir.file("out/paired.csv")));
  ASSERT_EQ(csv.size(), 3u);
  EXPECT_EQ(csv[1].at("row"), "mixed");
  EXPECT_EQ(csv[1].at("wins"), "2");
  EXPECT_EQ(csv[1].at("losses"), "3");
  EXPECT_EQ(csv[1].at("interval"), "sequences+seeds");
  EXPECT_EQ(csv[1].at("row_seeds"), "2");
  EXPECT_EQ(csv[0].at("interval"), "sequences");
  EXPECT_EQ(csv[0].at("seeds_low_mm"), "");
  EXPECT_EQ(csv[0].at("holm_reading"), "lower");
}

// Learning curves: every trained run is listed, one whose selection.json
// kept only the chosen epoch too; the reference rows evaluated on the
// curves' validation protocol are levels beside them, and one evaluated
// otherwise is a note.
TEST(Learning, EveryRunAndTheReferenceLevelsOnTheSameMeasure) {
  TempDir dir("report-learning");
  FakeRun net;
  testing::write_run(dir, "net", net);
  dir.write("net/selection.json",
            R"({"val_error_mm_by_epoch": [30.0, 25.0], "windows_by_epoch": [100, 100], "val_split": "val", )"
            R"("val_horizon": 27, "val_sequences": 0})");
  // Trained before the trainer kept every epoch: the chosen one only.
  FakeRun old;
  testing::write_run(dir, "old", old);
  dir.write("old/selection.json", R"({"chosen_epoch": 2, "best_val_error_mm": 21.5, "epochs_done": 3})");
  // skinned: evaluated on test and on val (27 frames, 2 sequences): a level.
  FakeRun skinned;
  skinned.model = "skinned";
  skinned.parameters = 0;
  testing::write_run(dir, "skinned", skinned);
  skinned.evaluated_on = "val";
  skinned.error = 19.25;
  testing::write_run(dir, "skinned", skinned);
  // static: on test only, so not on the curves' measure.
  FakeRun still;
  still.model = "static";
  still.parameters = 0;
  testing::write_run(dir, "static", still);
  const ReportResult r = write_report(
      tables_only({dir.file("net"), dir.file("old"), dir.file("skinned"), dir.file("static")}), dir.file("out"));
  const std::string md = read_text_file(r.report);
  EXPECT_NE(md.find("| net | 2 | 200 | 30.00, 25.00 (2), 25.00 | yes: the last epoch is the best |"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| old | 3 | - | best 21.50 (2); the other epochs' errors were not recorded"), std::string::npos)
      << md;
  EXPECT_NE(md.find("| skinned (reference, not trained) | - | - | 19.25 on the same measure | - |"), std::string::npos)
      << md;
  EXPECT_EQ(md.find("| static (reference"), std::string::npos) << md;

  std::vector<RunResults> runs;
  for (const char* name : {"net", "old", "skinned", "static"}) runs.push_back(load_run(dir.file(name)));
  EXPECT_TRUE(runs[1].curve.only_best);
  EXPECT_EQ(runs[0].curve.horizon, 27);
  std::vector<std::string> notes;
  const std::vector<ReferenceLevel> levels = curve_references(runs, &notes);
  ASSERT_EQ(levels.size(), 1u);
  EXPECT_EQ(levels[0].name, "skinned");
  EXPECT_DOUBLE_EQ(levels[0].error_mm, 19.25);
  // static's only evaluation is on test: not a candidate, so no note; a
  // val evaluation over other rollout frames is one.
  EXPECT_TRUE(notes.empty()) << ::testing::PrintToString(notes);
  dir.write("net/selection.json",
            R"({"val_error_mm_by_epoch": [30.0, 25.0], "val_split": "val", "val_horizon": 35, "val_sequences": 0})");
  runs[0] = load_run(dir.file("net"));
  EXPECT_TRUE(curve_references(runs, &notes).empty());
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_EQ(notes[0],
            "learning curves: skinned is not drawn as a reference level: evaluated on 2 val sequences over 27 "
            "frames, the curves on all val sequences over 35 frames");
}

}  // namespace
}  // namespace layers::report
