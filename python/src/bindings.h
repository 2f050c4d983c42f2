// The parts of the module `layers._core` (internal to python/): each
// binds one C++ library's surface, and numpy() hands a C++ vector to
// Python without a copy (the array owns it).
#pragma once

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <utility>
#include <vector>

namespace layers::python {

namespace py = pybind11;

template <typename T>
py::array_t<T> numpy(std::vector<T>&& values, std::vector<py::ssize_t> shape) {
  auto* owner = new std::vector<T>(std::move(values));
  py::capsule release(owner, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array_t<T>(shape, owner->data(), release);
}

void bind_data(py::module_& m);      // data_bindings.cpp: Dataset
void bind_measures(py::module_& m);  // measure_bindings.cpp: error, collisions, crossings
void bind_windows(py::module_& m);   // window_bindings.cpp: the loader's windows of an epoch
void bind_zoo(py::module_& m);       // zoo_bindings.cpp: models, rollout

}  // namespace layers::python
