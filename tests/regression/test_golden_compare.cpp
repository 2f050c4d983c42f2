// The comparison of the regression test (golden_compare.h) on metrics.json
// texts: a copy of the golden passes, a degraded one fails with a message
// naming the run, the metric, the golden value, the new value and the
// difference; tolerances, nulls, missing and new metrics.
#include <gtest/gtest.h>

#include <cmath>

#include "golden_compare.h"
#include "layers/core/error.h"
#include "temp_dir.h"

using namespace layers;

namespace {

std::string metrics_json(double error, double h, double jacket_error, int diverged) {
  auto stat = [](double v) { return "{\"mean\": " + std::to_string(v) + ", \"std\": 0.1, \"count\": 3}"; };
  return "{\"model\": \"m\", \"diverged\": " + std::to_string(diverged) +
         ", \"overall\": {\"error_mm\": " + stat(error) + ", \"h_collision\": " + stat(h) +
         ", \"l_collision\": {\"mean\": null, \"std\": null, \"count\": 0}}, \"per_type\": {\"jacket\": "
         "{\"error_mm\": " +
         stat(jacket_error) + ", \"h_collision\": " + stat(h) +
         "}},"
         " \"error_growth_mm_per_frame\": " +
         stat(0.5) + "}";
}

regression::Tolerances tolerances() {
  regression::Tolerances t;
  t.by_kind = {{"error_mm", {0.05, 0.02}},
               {"h_collision", {0.002, 0.05}},
               {"l_collision", {0.002, 0.05}},
               {"diverged", {0, 0}},
               {"error_growth_mm_per_frame", {0.02, 0.05}}};
  return t;
}

regression::Golden golden() {
  return {"layersnet", "layersnet", regression::metrics_from_json(metrics_json(10.0, 0.05, 12.0, 0), "golden")};
}

}  // namespace

TEST(GoldenCompare, ExtractsOverallPerTypeDivergenceAndGrowth) {
  const auto m = regression::metrics_from_json(metrics_json(10.0, 0.05, 12.0, 1), "x.json");
  EXPECT_DOUBLE_EQ(m.at("overall.error_mm"), 10.0);
  EXPECT_DOUBLE_EQ(m.at("per_type.jacket.error_mm"), 12.0);
  EXPECT_DOUBLE_EQ(m.at("diverged"), 1.0);
  EXPECT_DOUBLE_EQ(m.at("error_growth_mm_per_frame"), 0.5);
  EXPECT_TRUE(std::isnan(m.at("overall.l_collision")));
  EXPECT_EQ(m.count("overall.h_crossing"), 0u) << "a metrics.json without crossings has none";
  EXPECT_EQ(m.count("overall.l_collision_plain"), 0u) << "nor the paper's L-collision when it was not measured";
  const auto x = regression::metrics_from_json(
      R"({"overall": {"error_mm": {"mean": 1, "std": 0, "count": 1}, "h_crossing": {"mean": 0.25, "std": 0, "count": 1},
          "l_crossing": {"mean": null, "std": null, "count": 0},
          "l_collision_plain": {"mean": 0.125, "std": 0, "count": 1}}})",
      "x.json");
  EXPECT_DOUBLE_EQ(x.at("overall.h_crossing"), 0.25);
  EXPECT_DOUBLE_EQ(x.at("overall.l_collision_plain"), 0.125);
  EXPECT_TRUE(std::isnan(x.at("overall.l_crossing")));
  EXPECT_THROW(regression::metrics_from_json("{\"model\": 1}", "x.json"), InputError);
  EXPECT_THROW(regression::metrics_from_json("{oops", "x.json"), InputError);
}

TEST(GoldenCompare, SameMetricsAndSmallNoisePass) {
  EXPECT_TRUE(regression::compare(golden(), golden().metrics, tolerances()).empty());
  // 10 mm: allowed 0.05 + 2% = 0.25 mm.
  const auto near = regression::metrics_from_json(metrics_json(10.24, 0.0515, 12.2, 0), "new");
  EXPECT_TRUE(regression::compare(golden(), near, tolerances()).empty());
}

TEST(GoldenCompare, DegradedMetricsFailWithReadableMessage) {
  const auto worse = regression::metrics_from_json(metrics_json(13.0, 0.05, 12.0, 2), "new");
  const auto messages = regression::compare(golden(), worse, tolerances());
  ASSERT_EQ(messages.size(), 2u);
  EXPECT_EQ(messages[0],
            "run 'layersnet' (model layersnet): diverged moved: golden 0, new 2, difference +2, allowed +-0");
  EXPECT_EQ(messages[1],
            "run 'layersnet' (model layersnet): overall.error_mm moved: golden 10, new 13, difference +3 (+30.0%), "
            "allowed +-0.25");
}

TEST(GoldenCompare, MissingNewAndNullMetricsAreReported) {
  auto now = golden().metrics;
  now.erase("per_type.jacket.error_mm");
  now["per_type.dress.error_mm"] = 4.0;
  now["overall.l_collision"] = 0.1;  // the golden has null (no inner + outer pair)
  const auto messages = regression::compare(golden(), now, tolerances());
  ASSERT_EQ(messages.size(), 3u);
  EXPECT_NE(messages[0].find("overall.l_collision moved: golden null, new 0.1"), std::string::npos);
  EXPECT_NE(messages[1].find("per_type.jacket.error_mm missing"), std::string::npos);
  EXPECT_NE(messages[2].find("per_type.dress.error_mm is new"), std::string::npos);
}

TEST(GoldenCompare, GoldenFilesRoundTripAndUnknownKindsAreErrors) {
  test::TempDir dir;
  const std::string file = dir.write("g.json", regression::golden_json(golden()));
  const auto back = regression::read_golden(file);
  EXPECT_EQ(back.run, "layersnet");
  EXPECT_TRUE(regression::compare(back, golden().metrics, tolerances()).empty());
  regression::Tolerances partial;
  partial.by_kind = {{"error_mm", {0, 0}}};
  EXPECT_THROW(regression::compare(golden(), golden().metrics, partial), InputError);
  const std::string tol = dir.write("t.yaml", "error_mm: {abs: 0.05, rel: 0.02}\n");
  EXPECT_DOUBLE_EQ(regression::read_tolerances(tol).of("per_type.x.error_mm").rel, 0.02);
}
