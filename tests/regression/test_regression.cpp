// The CI regression test of the models (docs/studies.md): `layers run
// tests/regression/study.yaml` in a temporary folder on the synthetic
// fixture dataset the test writes there (synthetic_fixture.h), a very
// short deterministic train -> eval of every model whose plugin is built,
// then each run's eval-test/metrics.json against goldens/<run>.json within
// tolerances.yaml. The data are fixed, so the goldens depend only on the
// model and engine code; the generator has its own regression
// (test_generator_regression.cpp). The sha256 of the data used is printed.
//
//   LAYERS_UPDATE_GOLDENS=1   rewrite the goldens of the built models (on purpose)
//   LAYERS_REGRESSION_DIR=d   work in d and keep it (a second run reuses every step)
//
// A model whose plugin is not built is skipped with a message; a built one
// without a golden fails and says how to make it.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "golden_compare.h"
#include "layers/core/atomic_file.h"
#include "layers/core/error.h"
#include "layers/core/progress.h"
#include "layers/core/text_file.h"
#include "layers/study/runs.h"
#include "layers/zoo/plugin_loader.h"
#include "layers/zoo/registry.h"
#include "regression_paths.h"
#include "run_command.h"
#include "synthetic_fixture.h"
#include "temp_dir.h"

namespace fs = std::filesystem;
using namespace layers;

namespace {

using regression::golden_file;
using regression::regression_dir;
std::string study_file() { return regression_dir() + "/study.yaml"; }
bool updating() { return regression::updating_goldens(); }
// OpenBLAS picks its kernels by CPU (0.3.21, as installed: Haswell's on
// AMD CPUs with AVX2 or AVX-512, SkylakeX's on Intel AVX-512 ones), and
// LibTorch its own by CPU capability; MGNet's short training on the
// fixture amplifies the different rounding far past the tolerances (62.8
// against 66.4 mm between those BLAS kernels, 65.8 with LibTorch's
// "default" capability). The study runs with the AVX2 kernels of both
// wherever the CPU has AVX2 and FMA, so the goldens do not depend on
// those choices (a value already set is kept; the BLAS pin takes an
// OpenBLAS built with DYNAMIC_ARCH, as Debian's is). Empty where nothing
// is pinned.
std::string pinned_kernels() {
  std::string out;
  bool avx2 = false;
#if defined(__x86_64__) || defined(__i386__)
  avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
#endif
  const char* blas = std::getenv("OPENBLAS_CORETYPE");
  const char* aten = std::getenv("ATEN_CPU_CAPABILITY");
  if (blas || avx2) out += std::string("OPENBLAS_CORETYPE=") + (blas ? blas : "Haswell");
  if (aten || avx2) out += std::string(out.empty() ? "" : " ") + "ATEN_CPU_CAPABILITY=" + (aten ? aten : "avx2");
  return out;
}

std::string layers_command(const std::string& args) {
  const std::string kernels = pinned_kernels();
  return (kernels.empty() ? "" : kernels + " ") + "LAYERS_PLUGIN_PATH=" + test::plugin_dir() + " " +
         test::layers_bin() + " --log-level warn " + args;
}

// The study run once for every test of this binary.
struct Regression {
  std::unique_ptr<test::TempDir> temp;
  std::string work;                             // output and data live here
  std::string data;                             // the written fixture dataset
  std::map<std::string, std::string> model_of;  // run -> model name
  std::set<std::string> built;                  // runs whose model is registered
  test::CommandResult result;
  double seconds = 0;
  std::string setup_error;

  std::string runs() const { return work + "/runs"; }
  std::string metrics(const std::string& run) const { return runs() + "/" + run + "/eval-test/metrics.json"; }

  static Regression& get() {
    static Regression r = make();
    return r;
  }

 private:
  static Regression make() {
    Regression r;
    try {
      const char* keep = std::getenv("LAYERS_REGRESSION_DIR");
      if (keep && *keep) {
        r.work = keep;
        fs::create_directories(r.work);
      } else {
        r.temp = std::make_unique<test::TempDir>("layers-regression");
        r.work = r.temp->path();
      }
      // The synthetic fixture, written here: nothing in the source tree is written.
      r.data = regression::write_fixture(r.work);
      for (const char* f : {"shard-00000.h5", "splits.yaml"})
        std::printf("regression data: %s sha256 %s\n", f, regression::sha256_of(r.data + "/" + f).c_str());
      zoo::Registry registry;
      const fs::path bin_plugins = fs::path(test::layers_bin()).parent_path() / "plugins";
      zoo::load_all(registry, {test::plugin_dir(), bin_plugins.string()});
      const study::StudyConfig config = study::load_study(study_file());
      std::string only;
      for (const study::StudyRun& run : study::resolve_runs(config)) {
        const cfg::Node* name = run.config.model.find("name");
        r.model_of[run.name] = name ? name->scalar : "";
        if (name && registry.contains(name->scalar)) {
          r.built.insert(run.name);
          only += " --only '" + run.name + "'";
        }
      }
      if (r.built.empty()) throw Error("no model of the regression study is built");
      const std::string kernels = pinned_kernels();
      std::printf("regression kernels: %s\n",
                  kernels.empty() ? "OpenBLAS's and LibTorch's own choice" : kernels.c_str());
      Timer timer;
      r.result = test::run_command(layers_command("run " + study_file() + " --set output=" + r.runs() +
                                                  " --set dataset.folder=" + r.data + only));
      r.seconds = timer.seconds();
      // The study's own lines (steps, metrics), without progress lines.
      std::size_t start = 0;
      while (start < r.result.output.size()) {
        std::size_t end = r.result.output.find('\n', start);
        if (end == std::string::npos) end = r.result.output.size();
        const std::string line = r.result.output.substr(start, end - start);
        if (line.rfind("[regression]", 0) == 0 || line.rfind("  ", 0) == 0 ||
            line.find("steps ran") != std::string::npos)
          std::printf("%s\n", line.c_str());
        start = end + 1;
      }
      std::printf("regression study: %zu runs in %.1f s (working in %s)\n", r.built.size(), r.seconds, r.work.c_str());
    } catch (const std::exception& e) {
      r.setup_error = e.what();
    }
    return r;
  }
};

std::vector<std::string> study_runs() {
  try {
    std::vector<std::string> names;
    for (const auto& e : study::load_study(study_file()).experiments) names.push_back(e.name);
    return names;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "test_regression: cannot read %s: %s\n", study_file().c_str(), e.what());
    return {"unreadable_study"};
  }
}

std::string test_name(const testing::TestParamInfo<std::string>& info) {
  std::string s;
  for (char c : info.param)
    s += c == '+' ? std::string("_plus") : std::string(1, std::isalnum(static_cast<unsigned char>(c)) ? c : '_');
  return s;
}

}  // namespace

class RegressionRun : public testing::TestWithParam<std::string> {};

TEST_P(RegressionRun, MatchesGoldenMetrics) {
  const std::string run = GetParam();
  Regression& r = Regression::get();
  ASSERT_TRUE(r.setup_error.empty()) << r.setup_error;
  const std::string model = r.model_of.count(run) ? r.model_of.at(run) : "?";
  if (!r.built.count(run))
    GTEST_SKIP() << "model '" << model << "' (run '" << run << "') has no plugin in this build; its golden "
                 << golden_file(run) << " is checked once it is built";
  ASSERT_TRUE(fs::exists(r.metrics(run))) << "the study made no " << r.metrics(run) << "; `layers run` said:\n"
                                          << r.result.output;
  const regression::Metrics now = regression::metrics_from_json(read_text_file(r.metrics(run)), r.metrics(run));
  if (updating()) {
    write_text_atomic(golden_file(run), regression::golden_json({run, model, now}));
    std::printf("updated %s\n", golden_file(run).c_str());
    return;
  }
  ASSERT_TRUE(fs::exists(golden_file(run)))
      << "no golden for run '" << run << "' (model " << model << "): make it on purpose with\n"
      << "  LAYERS_UPDATE_GOLDENS=1 ctest -R regression   (or LAYERS_UPDATE_GOLDENS=1 build/bin/test_regression)\n"
      << "and commit " << golden_file(run);
  const regression::Golden golden = regression::read_golden(golden_file(run));
  const auto tolerances = regression::read_tolerances(regression::tolerances_file());
  for (const std::string& message : regression::compare(golden, now, tolerances)) ADD_FAILURE() << message;
}

INSTANTIATE_TEST_SUITE_P(Study, RegressionRun, testing::ValuesIn(study_runs()), test_name);

// The whole study again in the same folder: every step is current.
TEST(RegressionStudy, SecondRunReusesEveryStep) {
  Regression& r = Regression::get();
  ASSERT_TRUE(r.setup_error.empty()) << r.setup_error;
  ASSERT_EQ(r.result.exit_code, 0) << r.result.output;
  std::string only;
  for (const std::string& run : r.built) only += " --only '" + run + "'";
  const auto again = test::run_command(
      layers_command("run " + study_file() + " --set output=" + r.runs() + " --set dataset.folder=" + r.data + only));
  ASSERT_EQ(again.exit_code, 0) << again.output;
  EXPECT_NE(again.output.find("0 steps ran"), std::string::npos) << again.output;
  EXPECT_EQ(again.output.find(": running"), std::string::npos) << again.output;
}

// A deliberately degraded model -- the study's trainable run trained for a
// single optimiser step -- must fail the comparison with a readable
// message naming the run, the metric and both values.
TEST(RegressionStudy, DegradedModelFailsTheComparison) {
  Regression& r = Regression::get();
  ASSERT_TRUE(r.setup_error.empty()) << r.setup_error;
  // The largest trained model that is built (the test plugin always is).
  std::string run;
  for (const char* candidate : {"layersnet", "mgnet", "deepsd", "constant_velocity"})
    if (r.built.count(candidate) && fs::exists(golden_file(candidate))) {
      run = candidate;
      break;
    }
  if (run.empty()) GTEST_SKIP() << "no trained run with a golden yet";
  const std::string experiment = r.runs() + "/" + run + "/experiment.yaml";
  ASSERT_TRUE(fs::exists(experiment)) << r.result.output;
  test::TempDir dir("layers-degraded");
  const std::string sets = " --set run.output=" + dir.path() +
                           " --set train.epochs=1 --set train.windows_per_epoch=1 "
                           "--set train.batch_size=1 --quiet";
  const auto t = test::run_command(layers_command("train " + experiment + sets));
  ASSERT_EQ(t.exit_code, 0) << t.output;
  EXPECT_NE(t.output.find("(1 steps)"), std::string::npos) << t.output;
  const auto e = test::run_command(layers_command("eval " + experiment + sets));
  ASSERT_EQ(e.exit_code, 0) << e.output;
  const std::string metrics = dir.path() + "/eval-test/metrics.json";
  const auto messages = regression::compare(regression::read_golden(golden_file(run)),
                                            regression::metrics_from_json(read_text_file(metrics), metrics),
                                            regression::read_tolerances(regression::tolerances_file()));
  ASSERT_FALSE(messages.empty()) << "a model trained for one step matched the golden of '" << run << "'";
  bool named = false;
  for (const std::string& m : messages) {
    std::printf("degraded %s: %s\n", run.c_str(), m.c_str());
    named = named || (m.find("run '" + run + "'") != std::string::npos && m.find("golden ") != std::string::npos &&
                      m.find("new ") != std::string::npos);
  }
  EXPECT_TRUE(named) << messages.front();
}

// The evaluator's error growth rate (metrics.json) is the least-squares
// slope of the per-frame error before divergence. A slope is linear in the
// errors, so without divergence the mean of the sequences' slopes equals
// the slope of by_step (the mean error at each rollout step).
TEST(RegressionStudy, ErrorGrowthIsTheSlopeOfTheErrorCurve) {
  Regression& r = Regression::get();
  ASSERT_TRUE(r.setup_error.empty()) << r.setup_error;
  for (const std::string& run : r.built) {
    if (!fs::exists(r.metrics(run))) continue;  // reported by MatchesGoldenMetrics
    const auto doc = nlohmann::json::parse(read_text_file(r.metrics(run)));
    if (doc.at("diverged").get<int>() != 0) continue;
    double n = 0, sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (const auto& s : doc.at("by_step")) {
      const double x = s.at("step").get<double>(), y = s.at("error_mm").get<double>();
      n += 1, sx += x, sy += y, sxx += x * x, sxy += x * y;
    }
    const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
    const auto& growth = doc.at("error_growth_mm_per_frame");
    EXPECT_EQ(growth.at("count").get<int>(), doc.at("sequences").get<int>()) << run;
    EXPECT_NEAR(growth.at("mean").get<double>(), slope, 1e-6 * (1 + std::fabs(slope))) << run;
    for (const auto& s : doc.at("per_sequence")) EXPECT_TRUE(s.at("error_growth_mm_per_frame").is_number()) << run;
  }
}

// `layers bench` ran once per model on a tiny setting (study.yaml's bench
// step): bench.json has finite, positive inference times, and training
// times for the models with something to train. Figures only: no timed
// assertion.
TEST(RegressionStudy, BenchGivesFiniteFigures) {
  Regression& r = Regression::get();
  ASSERT_TRUE(r.setup_error.empty()) << r.setup_error;
  for (const std::string& run : r.built) {
    const std::string file = r.runs() + "/" + run + "/bench.json";
    ASSERT_TRUE(fs::exists(file)) << file << "; `layers run` said:\n" << r.result.output;
    const auto doc = nlohmann::json::parse(read_text_file(file));
    ASSERT_FALSE(doc.at("rows").empty()) << run;
    const bool trains = doc.at("parameters").get<double>() > 0;
    for (const auto& row : doc.at("rows")) {
      const double infer = row.at("ms_per_frame").get<double>(), train = row.at("train_ms_per_frame").get<double>();
      EXPECT_TRUE(std::isfinite(infer) && infer > 0) << run << ": " << infer;
      if (trains) {
        EXPECT_TRUE(std::isfinite(train) && train > 0) << run << ": " << train;
      }
    }
    EXPECT_GT(doc.at("peak_resident_mib").get<double>(), 0.0) << run;
  }
}
