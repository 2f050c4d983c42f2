// layers._core.epoch_windows: the training windows of one epoch in the
// order the C++ loader reads them (train/window_loader.h epoch_windows),
// for layers.WindowDataset (python/layers/windows.py).
#include <pybind11/stl.h>

#include <string>

#include "layers/core/error.h"

#include "bindings.h"
#include "layers/train/window_loader.h"

namespace layers::python {

void bind_windows(py::module_& m) {
  m.def(
      "epoch_windows",
      [](const data::Dataset& dataset, const std::string& split, const std::vector<std::string>& subsets,
         std::int64_t history, std::int64_t horizon, int stride, std::uint64_t seed, int epoch,
         int windows_per_epoch, int rank, int world) {
        // What `layers train` checks of the same settings (issue 62 S5).
        const auto refuse = [](const char* field, const char* expected, long long got) {
          throw InputError("layers.WindowDataset", field, expected, std::to_string(got));
        };
        if (history < 0) refuse("history", "0 or more frames before the window's start", history);
        if (horizon < 1) refuse("horizon", "1 or more frames after the window's start", horizon);
        if (stride < 1) refuse("stride", "1 or more", stride);
        if (world < 1) refuse("world", "1 or more processes", world);
        if (rank < 0 || rank >= world)
          refuse("rank", ("0 to world - 1 (" + std::to_string(world - 1) + ")").c_str(), rank);
        if (epoch < 0) refuse("epoch", "0 or more", epoch);
        if (windows_per_epoch < 0) refuse("windows_per_epoch", "0 (all) or more", windows_per_epoch);
        train::LoaderOptions options;
        options.split = split;
        options.subsets = subsets;
        options.history = history;
        options.stride = stride;
        options.seed = seed;
        options.windows_per_epoch = windows_per_epoch;
        options.rank = rank;
        options.world = world;
        const std::vector<std::string> ids = train::select_sequences(dataset, split, subsets);
        std::vector<std::pair<std::string, std::int64_t>> out;
        for (const train::WindowRef& w : train::epoch_windows(dataset, ids, options, epoch, horizon))
          out.emplace_back(w.id, w.start);
        return out;
      },
      "(sequence id, start frame) of every window of an epoch, in the C++ loader's order", py::arg("dataset"),
      py::arg("split"), py::arg("subsets"), py::arg("history"), py::arg("horizon"), py::arg("stride"),
      py::arg("seed"), py::arg("epoch"), py::arg("windows_per_epoch"), py::arg("rank"), py::arg("world"));
}

}  // namespace layers::python
