// Reading run folders (metrics.json and bench.json in the formats the
// evaluator and `layers bench` write) and the tables built from them;
// missing and malformed pieces give readable messages, never a crash.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "layers/core/error.h"
#include "layers/metrics/registry.h"
#include "layers/report/report.h"
#include "layers/report/tables.h"
#include "report_fixtures.h"

namespace layers::report {
namespace {

using layers::test::TempDir;
using testing::FakeRun;

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::vector<std::string> lines(const std::string& text) {
  std::vector<std::string> out;
  std::stringstream s(text);
  for (std::string line; std::getline(s, line);) out.push_back(line);
  return out;
}

std::vector<std::string> cells(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream s(line);
  for (std::string cell; std::getline(s, cell, ',');) out.push_back(cell);
  if (!line.empty() && line.back() == ',') out.emplace_back();
  return out;
}

// A table's lines without the columns of metrics registered after the six
// built-in ones: these tests pin the built-in layout, and a metric added to
// the registry (layers/metrics/registry.h) adds columns of its own.
std::vector<std::string> built_in_lines(const std::string& csv) {
  std::vector<std::string> added;
  const auto& defs = metrics::registered();
  for (std::size_t k = 6; k < defs.size(); ++k) added.push_back(defs[k].key);
  const std::vector<std::string> all = lines(csv);
  if (all.empty()) return all;
  const std::vector<std::string> header = cells(all[0]);
  std::vector<bool> keep(header.size(), true);
  for (std::size_t c = 0; c < header.size(); ++c)
    for (const std::string& key : added)
      if (header[c] == key || header[c] == key + "_std" || header[c] == "truth_" + key) keep[c] = false;
  std::vector<std::string> out;
  for (const std::string& line : all) {
    const std::vector<std::string> row = cells(line);
    std::string kept;
    bool first = true;
    for (std::size_t c = 0; c < row.size(); ++c) {
      if (c < keep.size() && !keep[c]) continue;
      kept += (first ? "" : ",") + row[c];
      first = false;
    }
    out.push_back(kept);
  }
  return out;
}

bool mentions(const std::vector<std::string>& problems, const std::string& text) {
  for (const std::string& p : problems)
    if (p.find(text) != std::string::npos) return true;
  return false;
}

TEST(RunResults, ParsesTheEvaluatorsMetrics) {
  FakeRun r;
  r.diverged_at = 12;
  const EvalResults e = parse_metrics(testing::metrics_json(r), "m.json");
  EXPECT_EQ(e.model, "mymodel");
  EXPECT_EQ(e.split, "test");
  EXPECT_EQ(e.sequences, 2);
  EXPECT_EQ(e.parameters, 1234);
  EXPECT_EQ(e.diverged, 1);
  EXPECT_DOUBLE_EQ(e.ms_per_frame, 2.0);
  EXPECT_DOUBLE_EQ(e.overall.get("error_mm").mean, 10.0);
  EXPECT_DOUBLE_EQ(e.overall.get("error_mm").std, 1.5);
  EXPECT_DOUBLE_EQ(e.truth_of("l_collision"), 0.0645);
  ASSERT_EQ(e.per_type.size(), 2u);
  EXPECT_EQ(e.per_type[1].first, "jumpsuit");
  EXPECT_TRUE(std::isnan(e.per_type[1].second.get("l_collision").mean)) << "count 0 means no value";
  ASSERT_EQ(e.by_step.size(), 3u);
  EXPECT_TRUE(std::isnan(e.by_step[0].get("l_collision"))) << "null means no value";
  EXPECT_DOUBLE_EQ(e.by_step[2].get("error_mm"), 3.0);
  // The exact crossings beside the vertex-normal rates.
  EXPECT_DOUBLE_EQ(e.overall.get("h_crossing").mean, 0.004);
  EXPECT_DOUBLE_EQ(e.overall.get("l_crossing").std, 0.002);
  EXPECT_EQ(e.overall.get("l_crossing").count, 2);
  EXPECT_DOUBLE_EQ(e.truth_of("h_crossing"), 0.0);
  EXPECT_DOUBLE_EQ(e.truth_of("l_crossing"), 0.0025);
  EXPECT_DOUBLE_EQ(e.per_type[0].second.get("h_crossing").mean, 0.003);
  EXPECT_TRUE(std::isnan(e.per_type[1].second.get("l_crossing").mean)) << "no L-crossing for an inner garment";
  EXPECT_DOUBLE_EQ(e.by_step[1].get("l_crossing"), 0.006);
  EXPECT_TRUE(std::isnan(e.by_step[0].get("l_crossing")));
  // The paper's L-collision beside ours.
  EXPECT_DOUBLE_EQ(e.overall.get("l_collision_plain").mean, 0.08);
  EXPECT_DOUBLE_EQ(e.overall.get("l_collision_plain").std, 0.01);
  EXPECT_DOUBLE_EQ(e.truth_of("l_collision_plain"), 0.0845);
  EXPECT_DOUBLE_EQ(e.per_type[0].second.get("l_collision_plain").mean, 0.08);
  EXPECT_TRUE(std::isnan(e.per_type[1].second.get("l_collision_plain").mean)) << "no L-collision for an inner garment";
  EXPECT_DOUBLE_EQ(e.by_step[1].get("l_collision_plain"), 0.08);
  EXPECT_TRUE(std::isnan(e.by_step[0].get("l_collision_plain")));
  // Absolute frame 12 is rollout step 11 (rollouts start at frames 0 and 1).
  EXPECT_EQ(e.first_divergence_step(), 11);
  r.diverged_at = -1;
  EXPECT_EQ(parse_metrics(testing::metrics_json(r), "m.json").first_divergence_step(), -1);
}

// A metrics.json written before the evaluator measured crossings and the
// paper's L-collision loads: those are absent (empty cells, "-"),
// everything else as before.
TEST(RunResults, MetricsWithoutCrossingsStillLoad) {
  TempDir dir("report-old-metrics");
  FakeRun old;
  old.crossings = false;
  old.plain = false;
  const std::string text = testing::metrics_json(old);
  ASSERT_EQ(text.find("crossing"), std::string::npos);
  ASSERT_EQ(text.find("plain"), std::string::npos);
  const EvalResults e = parse_metrics(text, "old.json");
  EXPECT_DOUBLE_EQ(e.overall.get("error_mm").mean, 10.0);
  EXPECT_DOUBLE_EQ(e.overall.get("h_collision").mean, 0.02);
  EXPECT_DOUBLE_EQ(e.truth_of("l_collision"), 0.0645);
  EXPECT_EQ(e.overall.get("h_crossing").count, 0);
  EXPECT_TRUE(std::isnan(e.overall.get("h_crossing").mean));
  EXPECT_TRUE(std::isnan(e.overall.get("l_crossing").mean));
  EXPECT_TRUE(std::isnan(e.truth_of("h_crossing")));
  EXPECT_TRUE(std::isnan(e.truth_of("l_crossing")));
  EXPECT_TRUE(std::isnan(e.per_type[0].second.get("h_crossing").mean));
  EXPECT_TRUE(std::isnan(e.by_step[1].get("h_crossing")));
  EXPECT_EQ(e.overall.get("l_collision_plain").count, 0);
  EXPECT_TRUE(std::isnan(e.overall.get("l_collision_plain").mean));
  EXPECT_TRUE(std::isnan(e.truth_of("l_collision_plain")));
  EXPECT_TRUE(std::isnan(e.per_type[0].second.get("l_collision_plain").mean));
  EXPECT_TRUE(std::isnan(e.by_step[1].get("l_collision_plain")));

  const std::vector<RunResults> runs = {load_run(testing::write_run(dir, "old", old))};
  ASSERT_TRUE(runs[0].eval.has_value()) << ::testing::PrintToString(runs[0].problems);
  EXPECT_EQ(built_in_lines(summary_csv(runs))[1],
            "old,mymodel,test,2,54,1234,2,10,1.5,0.02,0.01,0.05,0,,,,,,,0,0.0645,,,,0,,yes,unknown,unknown,test,,,,,"
            "old,");
  EXPECT_EQ(built_in_lines(per_type_csv(runs))[1], "old,mymodel,jacket,2,11,0.5,0.01,0,0.05,0,,,,,,");
  EXPECT_EQ(built_in_lines(by_step_csv(runs))[2], "old,mymodel,2,2,2,0.02,0.05,,,");
  ReportInputs inputs;
  inputs.runs = {runs[0].dir};
  inputs.gnuplot = dir.file("no-such-gnuplot");
  const std::string md = slurp(write_report(inputs, dir.file("out")).report);
  EXPECT_NE(md.find("| 10.0 ± 1.5 | 2.00% | 5.00% | - | - | - |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.00% / 6.45% / - / - / -"), std::string::npos) << md;
  EXPECT_NE(md.find("| jacket | old | 2 | 11.0 ± 0.5 | 1.00% | 5.00% | - | - | - |"), std::string::npos) << md;
}

// The run folders written before the paper's L-collision was measured (with
// crossings): only its cells are empty, and the report says why.
TEST(RunResults, MetricsWithoutThePapersLCollisionStillLoad) {
  TempDir dir("report-no-plain");
  FakeRun before;
  before.plain = false;
  const std::vector<RunResults> runs = {load_run(testing::write_run(dir, "before", before))};
  ASSERT_TRUE(runs[0].eval.has_value()) << ::testing::PrintToString(runs[0].problems);
  EXPECT_TRUE(std::isnan(runs[0].eval->overall.get("l_collision_plain").mean));
  EXPECT_DOUBLE_EQ(runs[0].eval->overall.get("l_collision").mean, 0.05);
  EXPECT_EQ(built_in_lines(summary_csv(runs))[1],
            "before,mymodel,test,2,54,1234,2,10,1.5,0.02,0.01,0.05,0,,,0.004,0.001,0.006,0.002,0,0.0645,,0,0.0025,0,,"
            "yes,unknown,unknown,test,,,,,before,");
  const auto doc = nlohmann::json::parse(summary_json("T", runs, {}, {}));
  EXPECT_TRUE(doc["runs"][0]["overall"]["l_collision_plain"]["mean"].is_null());
  EXPECT_TRUE(doc["runs"][0]["truth"]["l_collision_plain"].is_null());
  ReportInputs inputs;
  inputs.runs = {runs[0].dir};
  inputs.gnuplot = dir.file("no-such-gnuplot");
  const std::string md = slurp(write_report(inputs, dir.file("out")).report);
  EXPECT_NE(md.find("| 2.00% | 5.00% | - | 0.40% | 0.60% |"), std::string::npos) << md;
  EXPECT_NE(md.find("| 0.00% / 6.45% / - / 0.00% / 0.25%"), std::string::npos) << md;
  EXPECT_NE(md.find("an evaluation made before the metric existed"), std::string::npos) << md;
}

TEST(RunResults, MalformedFilesNameFileAndField) {
  try {
    parse_metrics("{ \"model\": \"x\", ", "bad.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("valid JSON"), std::string::npos) << e.what();
  }
  try {
    parse_metrics(R"({"model": "x", "overall": 3})", "m.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "overall");
    EXPECT_EQ(e.expected(), "an object");
  }
  try {
    parse_bench(R"({"model": "x", "rows": [{"level": 0, "ms_per_frame": "fast"}]})", "b.json");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.field(), "rows[0].ms_per_frame");
  }
}

TEST(Tables, SummaryPerTypeByStepAndBench) {
  TempDir dir("report-tables");
  FakeRun fast, slow, dominated;
  fast.model = "fastnet", fast.ms_per_frame = 1.0, fast.error = 20.0;
  slow.model = "slownet", slow.ms_per_frame = 10.0, slow.error = 5.0, slow.diverged_at = 20;
  dominated.model = "meh", dominated.ms_per_frame = 12.0, dominated.error = 8.0;
  const std::string a = testing::write_run(dir, "a_fast", fast);
  const std::string b = testing::write_run(dir, "b_slow", slow);
  const std::string c = testing::write_run(dir, "c_dominated", dominated);
  dir.write("b_slow/bench.json", testing::bench_json("slownet", 3.0, 11.0));
  const std::vector<RunResults> runs = {load_run(a), load_run(b), load_run(c)};
  EXPECT_EQ(runs[1].name, "b_slow");
  EXPECT_EQ(runs[1].dataset, "/nonexistent/dataset");
  ASSERT_TRUE(runs[1].bench.has_value());
  EXPECT_EQ(runs[1].bench->rows.size(), 3u);

  EXPECT_EQ(runs_on_front(runs), (std::vector<bool>{true, true, false}));
  const auto summary = built_in_lines(summary_csv(runs));
  ASSERT_EQ(summary.size(), 4u);
  // Each registered metric's mean and std in registry order, then the
  // ground truth's, divergence, Pareto, selection and seed columns.
  EXPECT_EQ(summary[0],
            "run,model,split,sequences,frames,parameters,ms_per_frame,error_mm,error_mm_std,h_collision,"
            "h_collision_std,l_collision,l_collision_std,l_collision_plain,l_collision_plain_std,h_crossing,"
            "h_crossing_std,l_crossing,l_crossing_std,truth_h_collision,truth_l_collision,truth_l_collision_plain,"
            "truth_h_crossing,truth_l_crossing,diverged,first_divergence_step,pareto,checkpoint,chosen_on,"
            "evaluated_on,chosen_epoch,epochs,val_error_mm,selection_flag,experiment,seed");
  EXPECT_EQ(summary[1],
            "a_fast,fastnet,test,2,54,1234,1,20,1.5,0.02,0.01,0.05,0,0.08,0.01,0.004,0.001,0.006,0.002,0,0.0645,0.0845,"
            "0,0.0025,0,,yes,unknown,unknown,test,,,,,a_fast,");
  EXPECT_EQ(summary[2],
            "b_slow,slownet,test,2,54,1234,10,5,1.5,0.02,0.01,0.05,0,0.08,0.01,0.004,0.001,0.006,0.002,0,0.0645,"
            "0.0845,0,0.0025,1,19,yes,unknown,unknown,test,,,,,b_slow,");
  EXPECT_NE(summary[3].find(",no,"), std::string::npos);

  const auto types = built_in_lines(per_type_csv(runs));
  ASSERT_EQ(types.size(), 7u);
  EXPECT_EQ(types[0],
            "run,model,type,sequences,error_mm,error_mm_std,h_collision,h_collision_std,l_collision,l_collision_std,"
            "l_collision_plain,l_collision_plain_std,h_crossing,h_crossing_std,l_crossing,l_crossing_std");
  EXPECT_EQ(types[1], "a_fast,fastnet,jacket,2,21,0.5,0.01,0,0.05,0,0.08,0,0.003,0.001,0.006,0.002");
  EXPECT_EQ(types[2], "a_fast,fastnet,jumpsuit,2,19,0.5,0.03,0,,,,,0.005,0.001,,")
      << "no L-collision or L-crossing for an inner garment";

  const auto steps = built_in_lines(by_step_csv(runs));
  ASSERT_EQ(steps.size(), 10u);
  EXPECT_EQ(steps[0],
            "run,model,step,sequences,error_mm,h_collision,l_collision,l_collision_plain,h_crossing,l_crossing");
  EXPECT_EQ(steps[1], "a_fast,fastnet,1,2,1,0.02,,,0.004,");
  EXPECT_EQ(steps[2], "a_fast,fastnet,2,2,2,0.02,0.05,0.08,0.004,0.006");

  const auto bench = lines(bench_csv(runs));
  ASSERT_EQ(bench.size(), 4u);
  EXPECT_EQ(bench[1], "b_slow,slownet,0,no,300,200,3,0,patches=12");
  EXPECT_EQ(bench[3], "b_slow,slownet,1,no,1200,200,11,4.5,");

  const auto doc = nlohmann::json::parse(summary_json("T", runs, {"p1"}, {"charts/x.png"}));
  ASSERT_EQ(doc["pareto_front"].size(), 2u);
  EXPECT_EQ(doc["pareto_front"][0]["run"], "a_fast");
  EXPECT_EQ(doc["pareto_front"][1]["run"], "b_slow");
  EXPECT_EQ(doc["runs"][1]["first_divergence_step"], 19);
  EXPECT_TRUE(doc["runs"][0]["per_type"]["jumpsuit"]["l_collision"]["mean"].is_null());
  EXPECT_DOUBLE_EQ(doc["runs"][0]["overall"]["h_crossing"]["mean"].get<double>(), 0.004);
  EXPECT_DOUBLE_EQ(doc["runs"][0]["truth"]["l_crossing"].get<double>(), 0.0025);
  EXPECT_DOUBLE_EQ(doc["runs"][0]["overall"]["l_collision_plain"]["mean"].get<double>(), 0.08);
  EXPECT_DOUBLE_EQ(doc["runs"][0]["truth"]["l_collision_plain"].get<double>(), 0.0845);
  EXPECT_TRUE(doc["runs"][0]["per_type"]["jumpsuit"]["l_collision_plain"]["mean"].is_null());
  EXPECT_EQ(doc["runs"][2]["pareto"], false);
  EXPECT_EQ(doc["problems"][0], "p1");
}

TEST(RunResults, FolderWithoutMetricsGivesAReadableMessage) {
  TempDir dir("report-missing");
  dir.write("empty_run/experiment.yaml", "data: {dataset: d}\nmodel: {name: m, params: {}}\n");
  const RunResults run = load_run(dir.file("empty_run"));
  EXPECT_FALSE(run.eval.has_value());
  EXPECT_EQ(run.model, "m");
  EXPECT_TRUE(mentions(run.problems, "no evaluation")) << ::testing::PrintToString(run.problems);
  EXPECT_TRUE(mentions(run.problems, "layers eval")) << ::testing::PrintToString(run.problems);
  EXPECT_TRUE(mentions(run.problems, "no bench.json"));

  const RunResults nothing = load_run(dir.file("not_there"));
  EXPECT_TRUE(mentions(nothing.problems, "no such run folder"));

  dir.write("broken/eval-test/metrics.json", "{\"model\": ");
  const RunResults broken = load_run(dir.file("broken"));
  EXPECT_FALSE(broken.eval.has_value());
  EXPECT_TRUE(mentions(broken.problems, "valid JSON")) << ::testing::PrintToString(broken.problems);

  ReportInputs inputs;
  inputs.runs = {dir.file("empty_run"), dir.file("not_there")};
  const ReportResult result = write_report(inputs, dir.file("out"));
  EXPECT_EQ(result.runs_with_metrics, 0u);
  const std::string md = slurp(result.report);
  EXPECT_NE(md.find("no evaluation"), std::string::npos);
  EXPECT_NE(md.find("no such run folder"), std::string::npos);
  EXPECT_NE(md.find("`empty_run` is not in the table"), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(dir.file("out/summary.csv")));
}

TEST(Report, MissingGnuplotStillWritesTheTables) {
  TempDir dir("report-nognuplot");
  const std::string run = testing::write_run(dir, "a", FakeRun{});
  ReportInputs inputs;
  inputs.runs = {run};
  inputs.gnuplot = dir.file("no-such-gnuplot");
  const ReportResult result = write_report(inputs, dir.file("out"));
  EXPECT_EQ(result.runs_with_metrics, 1u);
  EXPECT_TRUE(result.charts.empty());
  EXPECT_TRUE(mentions(result.problems, "gnuplot is missing")) << ::testing::PrintToString(result.problems);
  for (const char* f : {"report.md", "summary.csv", "summary.json", "per_type.csv", "by_step.csv", "bench.csv"})
    EXPECT_TRUE(std::filesystem::exists(dir.file(std::string("out/") + f))) << f;
  EXPECT_EQ(lines(slurp(dir.file("out/summary.csv"))).size(), 2u);
  const std::string md = slurp(result.report);
  EXPECT_NE(md.find("gnuplot is missing"), std::string::npos);
  EXPECT_NE(md.find("| a | mymodel | 1234 |"), std::string::npos) << md;
  // The paper's L-collision beside ours, each named for what it is; the
  // exact crossings and the truth's beside the vertex-normal rates,
  // explained in the note.
  EXPECT_NE(md.find("| error (mm) | H-collision | L-coll (ours: open-edge rule) | L-coll (paper: nearest vertex) | "
                    "H-crossing | L-crossing |"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 10.0 ± 1.5 | 2.00% | 5.00% | 8.00% | 0.40% | 0.60% |"), std::string::npos) << md;
  EXPECT_NE(md.find("| ground truth H-collision / L-coll (ours: open-edge rule) / L-coll (paper: nearest vertex) / "
                    "H-crossing / L-crossing"),
            std::string::npos)
      << md;
  EXPECT_NE(md.find("| 0.00% / 6.45% / 8.45% / 0.00% / 0.25%"), std::string::npos) << md;
  EXPECT_NE(md.find("| jacket | a | 2 | 11.0 ± 0.5 | 1.00% | 5.00% | 8.00% | 0.30% | 0.60% |"), std::string::npos)
      << md;
  // Each metric explained under the table, from its registry entry.
  EXPECT_NE(md.find("- **H-crossing**: share of garment vertices on a garment face that passes through a body face"),
            std::string::npos)
      << md;
  EXPECT_EQ(result.pareto_front, (std::vector<std::string>{"a"}));
}

}  // namespace
}  // namespace layers::report
