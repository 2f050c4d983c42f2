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
  EXPECT_DOUBLE_EQ(e.overall.error_mm.mean, 10.0);
  EXPECT_DOUBLE_EQ(e.overall.error_mm.std, 1.5);
  EXPECT_DOUBLE_EQ(e.truth_l_collision, 0.0645);
  ASSERT_EQ(e.per_type.size(), 2u);
  EXPECT_EQ(e.per_type[1].first, "jumpsuit");
  EXPECT_TRUE(std::isnan(e.per_type[1].second.l_collision.mean)) << "count 0 means no value";
  ASSERT_EQ(e.by_step.size(), 3u);
  EXPECT_TRUE(std::isnan(e.by_step[0].l_collision)) << "null means no value";
  EXPECT_DOUBLE_EQ(e.by_step[2].error_mm, 3.0);
  // Absolute frame 12 is rollout step 11 (rollouts start at frames 0 and 1).
  EXPECT_EQ(e.first_divergence_step(), 11);
  r.diverged_at = -1;
  EXPECT_EQ(parse_metrics(testing::metrics_json(r), "m.json").first_divergence_step(), -1);
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
  const auto summary = lines(summary_csv(runs));
  ASSERT_EQ(summary.size(), 4u);
  EXPECT_EQ(summary[0].substr(0, 42), "run,model,split,sequences,frames,parameter");
  EXPECT_EQ(summary[1], "a_fast,fastnet,test,2,54,1234,1,20,1.5,0.02,0.01,0.05,0,0,0.0645,0,,yes");
  EXPECT_EQ(summary[2], "b_slow,slownet,test,2,54,1234,10,5,1.5,0.02,0.01,0.05,0,0,0.0645,1,19,yes");
  EXPECT_EQ(summary[3].substr(summary[3].size() - 3), ",no");

  const auto types = lines(per_type_csv(runs));
  ASSERT_EQ(types.size(), 7u);
  EXPECT_EQ(types[1], "a_fast,fastnet,jacket,2,21,0.5,0.01,0,0.05,0");
  EXPECT_EQ(types[2], "a_fast,fastnet,jumpsuit,2,19,0.5,0.03,0,,") << "no L-collision for an inner garment";

  const auto steps = lines(by_step_csv(runs));
  ASSERT_EQ(steps.size(), 10u);
  EXPECT_EQ(steps[1], "a_fast,fastnet,1,1,0.02,,2");

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
  EXPECT_EQ(result.pareto_front, (std::vector<std::string>{"a"}));
}

}  // namespace
}  // namespace layers::report
