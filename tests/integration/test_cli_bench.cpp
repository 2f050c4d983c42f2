// `layers bench --simulator`: our simulator timed on the benchmarked scene
// at each level, beside the model, on a dataset `layers generate` made (a
// very small tiny.yaml: two scenes, one of them test); the same mesh at level 0, about the subdivided
// size at level 1; a dataset without a generator config is one line.
#include <gtest/gtest.h>

#include <cmath>
#include <nlohmann/json.hpp>

#include "file_bytes.h"
#include "run_command.h"
#include "synthetic_fixture.h"
#include "temp_dir.h"

using namespace layers;
using test::run_command;

namespace {

std::string experiment(test::TempDir& dir, const std::string& data) {
  return dir.write("exp.yaml",
                   "model: {name: test_constant_velocity, params: {damping: 0.6}}\n"
                   "data: {dataset: " +
                       data + "}\nrun: {output: " + dir.file("run") + ", threads: 1, seed: 0}\n");
}

std::string bench(const std::string& exp, const std::string& extra) {
  return "LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " + test::layers_bin() + " bench " + exp +
         " --min-time 0.01 --no-far-body --no-train " + extra;
}

}  // namespace

TEST(CliBench, SimulatorTimedOnTheSameSceneAtEachLevel) {
  test::TempDir dir;
  const std::string data = dir.file("ds");
  auto made = run_command(test::layers_bin() + " generate --config " + test::source_dir() +
                          "/configs/data/tiny.yaml --out " + data +
                          " --quiet --set sequences=2 --set frames=4 --set drape_frames=2"
                          " --set body.transition_frames=2 --set garments.fit.edge_length=0.1 --set splits.val=0"
                          " --set splits.test=0.5 --set sim.validation.max_l_penetration=1"
                          " --set sim.validation.max_h_penetration=1 --set sim.validation.max_stretch=100"
                          " --set sim.validation.max_h_crossing_clear=1");
  ASSERT_EQ(made.exit_code, 0) << made.output;
  const std::string out = dir.file("bench.json");
  auto timed = run_command(bench(experiment(dir, data), "--levels 1 --simulator --simulator-frames 2 --out " + out));
  ASSERT_EQ(timed.exit_code, 0) << timed.output;
  EXPECT_NE(timed.output.find("level 1, our simulator:"), std::string::npos) << timed.output;
  const nlohmann::json doc = nlohmann::json::parse(test::read_bytes(out));
  ASSERT_EQ(doc["rows"].size(), 2u) << doc.dump(1);
  for (const nlohmann::json& row : doc["rows"]) {
    const nlohmann::json& sim = row["simulator"];
    ASSERT_TRUE(sim.is_object()) << row.dump(1);
    const double model_vertices = row["garment_vertices"].get<double>();
    const double sim_vertices = sim["garment_vertices"].get<double>();
    if (row["level"] == 0)
      EXPECT_EQ(sim_vertices, model_vertices) << "level 0 is the stored mesh";
    else
      EXPECT_NEAR(sim_vertices / model_vertices, 1.0, 0.3) << "half the edge length is about one subdivision";
    EXPECT_GT(sim["ms_per_frame"].get<double>(), 0.0);
    const double speedup = sim["model_speedup"].get<double>();
    EXPECT_TRUE(std::isfinite(speedup) && speedup > 0) << speedup;
  }
  EXPECT_GT(doc["peak_resident_mib"].get<double>(), 0.0);

  // What the simulator cannot do is refused before any model is timed.
  auto too_many = run_command(
      bench(experiment(dir, data), "--levels 1 --simulator --simulator-frames 9 --out " + dir.file("frames.json")));
  EXPECT_EQ(too_many.exit_code, 1) << too_many.output;
  EXPECT_NE(too_many.output.find("/dataset.yaml: frames: expected 2..4, got 9"), std::string::npos) << too_many.output;
  EXPECT_EQ(too_many.output.find("infer ms/fr"), std::string::npos) << "nothing was timed";

  // The regression fixture was not made by the generator: one line, exit 1.
  test::TempDir other;
  const std::string synthetic = regression::write_fixture(other.path());
  auto refused =
      run_command(bench(experiment(other, synthetic), "--levels 0 --simulator --out " + other.file("b.json")));
  EXPECT_EQ(refused.exit_code, 1) << refused.output;
  EXPECT_NE(refused.output.find(synthetic + "/dataset.yaml: generator: expected the generator config"),
            std::string::npos)
      << refused.output;
}
