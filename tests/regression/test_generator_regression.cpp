// The generator's own regression (docs/studies.md): the committed
// generator settings tests/regression/generator.yaml (tiny's scenes at 20
// frames) are generated with the `layers` binary in a temporary folder, and the
// dataset's physical measures are compared with goldens/generator.json
// within tolerances.yaml. The generator is not bit-identical across CPUs
// (the simulation amplifies last-bit differences of libm's CPU-dispatched
// functions, docs/studies.md), so the goldens are physical measures with
// tolerances, never bytes. The test prints the sha256 of the shard it made,
// so two machines can be compared.
//
//   LAYERS_UPDATE_GOLDENS=1   rewrite goldens/generator.json (on purpose)
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "golden_compare.h"
#include "layers/core/atomic_file.h"
#include "layers/core/config.h"
#include "layers/data/dataset.h"
#include "layers/generate/stored_measures.h"
#include "layers/sim/measures.h"
#include "regression_paths.h"
#include "run_command.h"
#include "synthetic_fixture.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;

namespace {

// Mean speed of the garment vertices, mm per frame, over every frame step.
double garment_speed_mm(const data::SequenceData& seq) {
  double sum = 0;
  std::int64_t n = 0;
  for (const auto& g : seq.garments) {
    const std::size_t per_frame = g.positions.size() / static_cast<std::size_t>(seq.n_frames);
    for (std::int64_t t = 1; t < seq.n_frames; ++t)
      for (std::size_t i = 0; i < per_frame; i += 3) {
        const float* a = &g.positions[(t - 1) * per_frame + i];
        const float* b = &g.positions[t * per_frame + i];
        sum += std::sqrt(double(b[0] - a[0]) * (b[0] - a[0]) + double(b[1] - a[1]) * (b[1] - a[1]) +
                         double(b[2] - a[2]) * (b[2] - a[2]));
        ++n;
      }
  }
  return n > 0 ? 1000 * sum / n : 0;
}

// The physical measures of a dataset folder, as the generator's validation
// defines them (layers/sim/measures.h), over all its sequences.
regression::Metrics physical_measures(const std::string& folder) {
  const data::Dataset dataset = data::Dataset::open(folder);
  sim::SequenceMeasures all;
  double speed = 0, worst_stretch_sum = 0;
  for (const std::string& id : dataset.ids()) {
    const data::SequenceData seq = dataset.read_sequence(id);
    sim::SequenceMeasures one;
    generate::for_each_stored_frame(seq, [&](std::int64_t, const generate::StoredFrame& f) {
      const sim::FrameMeasures m = sim::measure_frame(f.body, f.garments);
      one.add(m);
      all.add(m);
    });
    worst_stretch_sum += one.max_stretch();
    speed += garment_speed_mm(seq);
  }
  const double n = static_cast<double>(dataset.ids().size());
  return {{"generator.sequences", n},
          {"generator.frames", static_cast<double>(all.frames())},
          {"generator.nonfinite", static_cast<double>(all.nonfinite())},
          {"generator.h_penetration", all.mean_h_penetration()},
          {"generator.l_penetration", all.mean_l_penetration()},
          {"generator.max_stretch", all.max_stretch()},
          {"generator.mean_h_crossing", all.mean_h_crossing()},
          {"generator.mean_l_crossing", all.mean_l_crossing()},
          {"generator.worst_l_crossing", all.max_l_crossing()},
          {"generator.mean_max_stretch", worst_stretch_sum / n},
          {"generator.garment_speed_mm_per_frame", speed / n}};
}

// Generates the committed generator settings (plus `extra` overrides) into
// `out`; "" on success, else the command and its output.
std::string generate_dataset(const std::string& out, const std::string& extra = "") {
  const std::string cmd = test::layers_bin() + " --log-level warn generate --config " + regression::generator_config() +
                          " --out " + out + " --threads 2 --quiet " + extra;
  const auto gen = test::run_command(cmd);
  return gen.exit_code == 0 ? "" : cmd + "\n" + gen.output;
}

}  // namespace

TEST(GeneratorRegression, PhysicalMeasuresMatchTheGoldens) {
  test::TempDir dir("layers-generator-regression");
  const std::string out = dir.file("data");
  const std::string failed = generate_dataset(out);
  ASSERT_TRUE(failed.empty()) << failed;
  EXPECT_EQ(test::run_command(test::layers_bin() + " validate " + out).exit_code, 0);

  std::printf("generated shard sha256 %s\n", regression::sha256_of(out + "/shard-00000.h5").c_str());

  const regression::Metrics now = physical_measures(out);
  for (const auto& [name, value] : now) std::printf("  %-40s %.6g\n", name.c_str(), value);
  const std::string golden_path = regression::golden_file("generator");
  if (regression::updating_goldens()) {
    write_text_atomic(golden_path, regression::golden_json({"generator", "generator", now}));
    std::printf("updated %s\n", golden_path.c_str());
    return;
  }
  ASSERT_TRUE(fs::exists(golden_path)) << "no " << golden_path << ": make it on purpose with LAYERS_UPDATE_GOLDENS=1";
  const auto messages = regression::compare(regression::read_golden(golden_path), now,
                                            regression::read_tolerances(regression::tolerances_file()));
  for (const std::string& m : messages) ADD_FAILURE() << m;
}

// The synthetic fixture the model goldens run on (synthetic_fixture.h) is a
// complete and valid LAYERS-H5 dataset.
TEST(GeneratorRegression, FixtureIsAValidDataset) {
  test::TempDir dir("layers-fixture");
  const std::string fixture = regression::write_fixture(dir.path());
  const auto valid = test::run_command(test::layers_bin() + " validate " + fixture);
  EXPECT_EQ(valid.exit_code, 0) << valid.output;
}

// A deliberately degraded generator -- the same scenes with a quarter of the
// solver's substeps and no validation -- must fail the comparison with a
// line naming the measure and both values.
TEST(GeneratorRegression, DegradedSolverFailsTheComparison) {
  test::TempDir dir("layers-generator-degraded");
  const std::string golden_path = regression::golden_file("generator");
  if (!fs::exists(golden_path)) GTEST_SKIP() << "no " << golden_path << " yet";
  const std::string out = dir.file("data");
  const std::string failed =
      generate_dataset(out,
                       "--set sim.substeps=3 --set sim.validation.max_h_penetration=1 "
                       "--set sim.validation.max_l_penetration=1 --set sim.validation.max_stretch=100");
  ASSERT_TRUE(failed.empty()) << failed;
  const regression::Metrics now = physical_measures(out);
  const auto messages = regression::compare(regression::read_golden(golden_path), now,
                                            regression::read_tolerances(regression::tolerances_file()));
  for (const std::string& m : messages) std::printf("degraded generator: %s\n", m.c_str());
  ASSERT_FALSE(messages.empty()) << "a solver with 3 substeps matched the generator goldens";
  EXPECT_NE(messages.front().find("golden "), std::string::npos) << messages.front();
}
