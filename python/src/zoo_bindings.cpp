// The model zoo from Python: layers._core.models() lists the registered
// models and layers._core.rollout() rolls a trained experiment out on one
// sequence with the same C++ code as `layers rollout` (train/evaluator.h
// run_evaluation: predictions.h5 and metrics.json in `out`). Plugins are
// found as the CLI finds them (zoo/plugin_loader.h: LAYERS_PLUGIN_PATH
// first), then beside this module: <build>/bin/plugins from the build
// tree, <prefix>/lib/layers/plugins from an install.
#include <dlfcn.h>
#include <pybind11/stl.h>

#include <filesystem>

#include "bindings.h"
#include "layers/core/config.h"
#include "layers/core/error.h"
#include "layers/data/run_layout.h"
#include "layers/train/evaluator.h"
#include "layers/train/experiment_config.h"
#include "layers/zoo/plugin_loader.h"

namespace layers::python {
namespace {

namespace fs = std::filesystem;

struct Zoo {
  zoo::Registry registry;
  zoo::LoadReport report;
};

Zoo& plugins() {
  static Zoo z;
  static bool loaded = false;
  if (!loaded) {
    loaded = true;
    std::vector<std::string> dirs = zoo::plugin_search_path();
    Dl_info info{};
    if (dladdr(reinterpret_cast<void*>(&plugins), &info) && info.dli_fname) {
      const fs::path here = fs::path(info.dli_fname).parent_path();
      for (const fs::path& d : {here / "../../bin/plugins", here / "../../../layers/plugins"}) {
        std::error_code ec;
        if (fs::is_directory(d, ec)) dirs.push_back(fs::canonical(d).string());
      }
    }
    z.report = zoo::load_all(z.registry, dirs);
  }
  return z;
}

}  // namespace

void bind_zoo(py::module_& m) {
  m.def(
      "models", [] { return plugins().registry.names(); }, "names of the registered models (plugins loaded once)");
  m.def(
      "plugin_problems",
      [] {
        std::vector<std::string> out;
        for (const zoo::PluginProblem& p : plugins().report.problems) out.push_back(p.message);
        return out;
      },
      "plugins that were refused, one line each");
  m.def(
      "rollout",
      [](const std::string& experiment, const std::string& sequence, const std::string& out,
         const std::string& checkpoint, int horizon, const std::vector<std::string>& sets) {
        if (horizon < -1)
          throw InputError("layers.rollout", "horizon",
                           "0 (to the end of the sequence), -1 (the experiment's eval.horizon) or a number of frames",
                           std::to_string(horizon));
        cfg::Node tree = cfg::load_file(experiment);
        for (const std::string& s : sets) cfg::apply_set(tree, s);
        train::ExperimentConfig config = train::read_experiment(tree, experiment);
        config.eval.save_predictions = true;
        train::EvalOptions options;
        options.checkpoint = checkpoint;
        options.horizon = horizon;
        options.out_dir = out;
        options.sequences = {sequence};
        options.progress = false;
        train::EvalReport report;
        {
          py::gil_scoped_release release;
          report = train::run_evaluation(config, plugins().registry, options);
        }
        py::dict d;
        d["model"] = report.model;
        d["checkpoint"] = report.checkpoint;
        d["predictions"] = (fs::path(report.out_dir) / data::run_layout::kPredictions).string();
        d["metrics"] = (fs::path(report.out_dir) / data::run_layout::kMetrics).string();
        d["frames"] = report.frames;
        d["diverged"] = report.diverged;
        return d;
      },
      "roll an experiment's model out on one sequence as `layers rollout` does; writes predictions.h5 and "
      "metrics.json into `out`",
      py::arg("experiment"), py::arg("sequence"), py::arg("out"), py::arg("checkpoint") = "best",
      py::arg("horizon") = 0, py::arg("sets") = std::vector<std::string>{});
}

}  // namespace layers::python
