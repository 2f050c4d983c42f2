// The module `layers._core` (python/CMakeLists.txt): its errors -- every
// C++ layers::Error reaches Python as layers.Error (an InputError as its
// subclass layers.InputError, with file, field, expected and got), its
// message the C++ line -- and the parts bound in data_bindings.cpp and
// measure_bindings.cpp, window_bindings.cpp and zoo_bindings.cpp.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "layers/core/error.h"

namespace py = pybind11;

PYBIND11_MODULE(_core, m) {
  m.doc() = "layers: LAYERS-H5 datasets and the evaluation's measures, bound from the C++ toolkit";
  static py::exception<layers::Error> error(m, "Error");
  static py::exception<layers::InputError> input_error(m, "InputError", error.ptr());
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const layers::InputError& e) {
      // The one line as the message, and its parts for programs.
      py::object instance = py::reinterpret_borrow<py::object>(input_error.ptr())(e.what());
      instance.attr("file") = e.file();
      instance.attr("field") = e.field();
      instance.attr("expected") = e.expected();
      instance.attr("got") = e.got();
      PyErr_SetObject(input_error.ptr(), instance.ptr());
    } catch (const layers::Error& e) {
      PyErr_SetString(error.ptr(), e.what());
    }
  });
  layers::python::bind_data(m);
  layers::python::bind_measures(m);
  layers::python::bind_windows(m);
  layers::python::bind_zoo(m);
}
