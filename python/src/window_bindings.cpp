// layers._core.epoch_windows: the training windows of one epoch in the
// order the C++ loader reads them (train/window_loader.h epoch_windows),
// for layers.WindowDataset (python/layers/windows.py).
#include <pybind11/stl.h>

#include "bindings.h"
#include "layers/train/window_loader.h"

namespace layers::python {

void bind_windows(py::module_& m) {
  m.def(
      "epoch_windows",
      [](const data::Dataset& dataset, const std::string& split, const std::vector<std::string>& subsets,
         std::int64_t history, std::int64_t horizon, int stride, std::uint64_t seed, int epoch,
         int windows_per_epoch, int rank, int world) {
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
